#include "cache/VisibleFill.h"

namespace raycache {

const char* visibleFillName(VisibleFill fill) {
    switch (fill) {
        case VisibleFill::Off: return "off";
        case VisibleFill::Exact: return "exact";
        case VisibleFill::Approximate: return "approximate";
    }
    return "off";
}

}  // namespace raycache
