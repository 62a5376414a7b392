#pragma once
// An environment variable set for one scope and given back its value (or
// removed again) when the scope ends: test cases of one program share the
// process's environment, and one that changed it would change the rest.
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace raycache::test {

class ScopedEnvironment {
public:
    ScopedEnvironment(std::string name, const std::string& value) : name_(std::move(name)) {
        if (const char* before = std::getenv(name_.c_str())) before_ = before;
        set(value);
    }
    ~ScopedEnvironment() {
        if (before_)
            setenv(name_.c_str(), before_->c_str(), /*overwrite=*/1);
        else
            unsetenv(name_.c_str());
    }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

    void set(const std::string& value) const { setenv(name_.c_str(), value.c_str(), /*overwrite=*/1); }
    void unset() const { unsetenv(name_.c_str()); }

private:
    std::string name_;
    std::optional<std::string> before_;
};

}  // namespace raycache::test
