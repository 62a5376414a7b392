#pragma once
// How the viewer shows the Render Cache pipeline (`--render-cache-display`):
// synchronously, one request map traced per displayed frame (the frames of
// `raycache render`, bit for bit), or asynchronously, the display
// reconstructing at its own rate while a tracer thread feeds it samples
// (rendercache/AsyncRenderCache.h).
#include <array>

namespace raycache {

enum class RenderCacheDisplay { Sync, Async };

inline constexpr std::array kRenderCacheDisplays{RenderCacheDisplay::Async, RenderCacheDisplay::Sync};

inline const char* renderCacheDisplayName(RenderCacheDisplay d) {
    return d == RenderCacheDisplay::Async ? "async" : "sync";
}

}  // namespace raycache
