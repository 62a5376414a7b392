#pragma once
// The asynchronous display's reshading budget (AsyncRenderCache): reshading
// the mirror, glass and glossy samples from the new eye is the largest part
// of a display frame on scenes full of mirrors, so the display reshades them
// in turns (RenderCacheSettings::reshadeInterval), choosing after each moving
// frame the interval that keeps reshading within a number of milliseconds.
// A frame's reshading costs about (samples to reshade) / interval, so one
// measured frame tells what every sample would cost. The interval grows at
// once when a frame runs over, and shrinks one step at a time, only when the
// smaller interval would still leave a quarter of the budget free: a display
// whose interval flips every frame shows reflections lagging by turns.
namespace raycache {

// The viewer's budget: a quarter of a frame at 30 fps.
inline constexpr double kDefaultReshadeBudgetMs = 8.0;

// The interval for the next moving frame, after one that reshaded with
// `interval` in `reshadeMs`; `budgetMs` <= 0: every sample every frame (1).
// Within 1 .. kMaxReshadeInterval.
int reshadeIntervalWithin(double budgetMs, int interval, double reshadeMs);

}  // namespace raycache
