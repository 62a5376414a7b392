#include "trace/EmbreeVersion.h"

#include <embree3/rtcore_config.h>

namespace raycache {

std::string embreeVersion() {
    return RTC_VERSION_STRING;
}

}  // namespace raycache
