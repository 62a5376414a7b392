#pragma once
// An experiment run on another process of an MPI job (`mpirun -np N raycache
// bench`, docs/cluster.md), brought to process 0: what it returned and every
// file it wrote into its results directory, as bytes. Process 0 then holds
// the same results/<name>/ as a single-process run, and the nodes need not
// share a file system.
#include <filesystem>

#include "bench/Experiment.h"
#include "core/ProcessGroup.h"

namespace raycache {

// Appends `output` and the files under `dir` (recursively, paths relative to it).
void packExperiment(Bytes& out, const ExperimentOutput& output, const std::filesystem::path& dir);

// Reads what packExperiment wrote, writes its files under `dir` (each one
// atomically, directories created) and returns the output. Throws
// std::runtime_error on a malformed message or a path leaving `dir`, and
// RuntimeError when a file cannot be written.
ExperimentOutput unpackExperiment(ByteReader& reader, const std::filesystem::path& dir);

}  // namespace raycache
