#pragma once
// Output names with one printf-style frame number, e.g. out/frame_%04d.png.
#include <optional>
#include <string>

namespace raycache {

class FramePathPattern {
public:
    // Throws InputError if `pattern` has a '%' that is not a single %d / %0Nd.
    explicit FramePathPattern(std::string pattern);

    bool perFrame() const { return width_.has_value(); }
    // The path for `frame`; the pattern itself when it has no frame number.
    std::string pathFor(int frame) const;

private:
    std::string prefix_, suffix_;
    std::optional<int> width_;  // zero-padding width, 0 for plain %d
};

}  // namespace raycache
