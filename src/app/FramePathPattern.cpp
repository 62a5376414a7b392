#include "app/FramePathPattern.h"

#include <cctype>

#include "core/Errors.h"

namespace raycache {

FramePathPattern::FramePathPattern(std::string pattern) {
    const auto percent = pattern.find('%');
    if (percent == std::string::npos) {
        prefix_ = std::move(pattern);
        return;
    }
    std::size_t i = percent + 1;
    int width = 0;
    if (i < pattern.size() && pattern[i] == '0') {
        ++i;
        while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) && width < 100)
            width = width * 10 + (pattern[i++] - '0');
    }
    if (i >= pattern.size() || pattern[i] != 'd' || width > 12 ||
        pattern.find('%', i + 1) != std::string::npos)
        throw InputError("--out '" + pattern + "': a frame number must be written %d or %0Nd, once");
    prefix_ = pattern.substr(0, percent);
    suffix_ = pattern.substr(i + 1);
    width_ = width;
}

std::string FramePathPattern::pathFor(int frame) const {
    if (!width_) return prefix_;
    std::string number = std::to_string(frame);
    if (static_cast<int>(number.size()) < *width_)
        number.insert(0, static_cast<std::size_t>(*width_) - number.size(), '0');
    return prefix_ + number + suffix_;
}

}  // namespace raycache
