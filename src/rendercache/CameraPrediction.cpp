#include "rendercache/CameraPrediction.h"

namespace raycache {

Camera predictNextCamera(const Camera& previous, const Camera& current) {
    Camera next = current;
    next.position = current.position + (current.position - previous.position);
    next.lookAt = current.lookAt + (current.lookAt - previous.lookAt);
    return next;
}

}  // namespace raycache
