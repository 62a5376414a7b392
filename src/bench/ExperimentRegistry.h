#pragma once
// Every experiment `raycache bench` can run, in the order `bench all` runs them.
#include <memory>
#include <string>
#include <vector>

#include "bench/Experiment.h"

namespace raycache {

std::vector<std::unique_ptr<Experiment>> allExperiments();

// The experiments named (each once, in the given order; "all" = every one).
// Throws InputError naming an unknown experiment and listing the known ones.
std::vector<std::unique_ptr<Experiment>> selectExperiments(const std::vector<std::string>& names);

}  // namespace raycache
