#pragma once
// What a pixel of a Render Cache frame shows, from reprojection to the image.

namespace raycache {

enum class PixelState : unsigned char {
    Reprojected,  // a sample from an earlier frame landed here
    Fresh,        // traced this frame
    Culled,       // a sample landed here, but its neighbourhood is markedly nearer: hidden
    Hole,         // no sample
    Filled3x3,    // a hole the 3x3 filter filled
    Filled7x7,    // a hole only the 7x7 prefilter reached
    Unfilled,     // a hole neither filter reached: the background shows
};

inline bool showsSample(PixelState s) { return s == PixelState::Reprojected || s == PixelState::Fresh; }
inline bool isHole(PixelState s) { return s == PixelState::Hole || s == PixelState::Culled; }

}  // namespace raycache
