#include "app/BenchCommand.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

#include "bench/ExperimentRegistry.h"
#include "bench/ExperimentTransfer.h"
#include "bench/MachineLoad.h"
#include "bench/Report.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/Parallel.h"
#include "core/ProcessAgreement.h"
#include "core/ScratchDirectory.h"
#include "render/TileAssignment.h"

namespace raycache {

namespace {

void printOutput(ProgressBar& progress, const ExperimentOutput& output, const std::filesystem::path& dir,
                 const std::string& ranOn = "") {
    progress.note(output.title + ranOn);
    for (const std::string& c : output.caveats) progress.note("  note: " + c);
    for (const std::string& h : output.headlines) progress.note("  " + h);
    progress.note("  wrote " + (dir / "results.md").string());
}

}  // namespace

void runBenchCommand(const BenchCommandOptions& options, std::ostream& out, const ProcessGroup& group) {
    if (options.list) {
        for (const auto& e : allExperiments()) out << e->name() << "  " << e->title() << "\n";
        return;
    }
    std::vector<std::unique_ptr<Experiment>> experiments;
    bool wholeReport = false;
    BenchSettings settings;
    // Every process checks the same options; a results directory that
    // process 0 cannot create stops all of them together.
    runOnEveryProcess(group, [&] {
        if (static_cast<int>(options.quick) + static_cast<int>(options.full) + static_cast<int>(options.tiny) > 1)
            throw InputError("choose one of --quick, --full and --tiny");
        if (options.threads < 0 || options.threads > 1024)
            throw InputError("--threads must be between 0 (all) and 1024");
        if (options.outDir.empty()) throw InputError("--out must name a directory");
        experiments = selectExperiments(options.experiments);
        wholeReport =
            std::find(options.experiments.begin(), options.experiments.end(), "all") != options.experiments.end();
        settings.size = options.full ? BenchSize::Full : options.tiny ? BenchSize::Tiny : BenchSize::Quick;
        settings.threads = options.threads;
        settings.outDir = options.outDir;
        settings.cachePolicy = options.cachePolicy;
        if (!group.isRoot()) return;
        std::error_code ec;
        std::filesystem::create_directories(settings.outDir, ec);
        if (ec || !std::filesystem::is_directory(settings.outDir))
            throw RuntimeError("cannot create the results directory " + settings.outDir.string() + ": " +
                               ec.message());
    });

    // Which process runs which experiment: longest estimated first, each to
    // the least loaded process (the same on every process).
    std::vector<double> work;
    for (const auto& e : experiments) work.push_back(e->estimatedWork(settings));
    const std::vector<int> owners = group.size() > 1 ? balancedTileOwners(work, group.size())
                                                     : std::vector<int>(experiments.size(), 0);
    // A process other than 0 writes its experiments into a directory of its
    // own, removed once they are sent to process 0.
    std::optional<ScratchDirectory> scratch;
    if (!group.isRoot()) scratch.emplace("raycache-bench-");
    const std::filesystem::path myOutDir = scratch ? scratch->path() : settings.outDir;

    const Parallel parallel(settings.threads);
    const LoadAverage loadBefore = currentLoadAverage();
    const CpuSample cpuBefore = currentCpuSample();
    const RunEnvironment environment = currentRunEnvironment(parallel.threadCount());
    double myWork = 0.0;
    std::size_t myCount = 0;
    for (std::size_t i = 0; i < experiments.size(); ++i)
        if (owners[i] == group.rank()) {
            myWork += work[i];
            ++myCount;
        }

    out << "raycache bench: " << experiments.size() << " experiment" << (experiments.size() == 1 ? "" : "s") << ", "
        << toString(settings.size) << " size, " << parallel.threadCount() << " threads, results in "
        << settings.outDir.string() << "/";
    if (group.size() > 1)
        out << " (over " << group.size() << " processes, " << myCount << " on process 0; its progress below)";
    out << std::endl;
    ProgressBar progress(out, options.interactive, myWork);
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::optional<ExperimentOutput>> outputs(experiments.size());
    Bytes mine;  // another process's experiments, for process 0
    appendBytes(mine, static_cast<std::uint64_t>(myCount));
    for (std::size_t i = 0; i < experiments.size(); ++i) {
        if (owners[i] != group.rank()) continue;
        const Experiment& e = *experiments[i];
        ExperimentContext context{settings, parallel, progress, environment, myOutDir / e.name()};
        std::error_code ec;
        std::filesystem::create_directories(context.dir, ec);
        if (ec) throw RuntimeError("cannot create " + context.dir.string() + ": " + ec.message());
        ExperimentOutput output = e.run(context);
        if (settings.cachePolicy != CachePolicyMode::Always && !e.honoursCachePolicy())
            output.caveats.push_back("--cache-policy " + std::string(cachePolicyModeName(settings.cachePolicy)) +
                                     " not applied: this experiment's protocol caches every frame (always)");
        printOutput(progress, output, context.dir);
        if (!group.isRoot()) {
            appendBytes(mine, static_cast<std::uint64_t>(i));
            packExperiment(mine, output, context.dir);
        }
        outputs[i] = std::move(output);
    }
    progress.finish();
    if (group.size() > 1) {
        GatheredBytes all;
        group.gatherToRoot(mine, all);
        for (std::size_t r = 1; r < all.count(); ++r) {
            ByteReader reader(all.of(r));
            const auto count = reader.read<std::uint64_t>();
            for (std::uint64_t k = 0; k < count; ++k) {
                const auto i = static_cast<std::size_t>(reader.read<std::uint64_t>());
                if (i >= experiments.size()) throw std::runtime_error("bench results from another process out of range");
                const std::filesystem::path dir = settings.outDir / experiments[i]->name();
                outputs[i] = unpackExperiment(reader, dir);
                printOutput(progress, *outputs[i], dir, " (process " + std::to_string(r) + ")");
            }
        }
        if (!group.isRoot()) return;
    }

    ReportInput report{.settings = settings, .environment = environment};
    for (std::optional<ExperimentOutput>& o : outputs)
        if (o) report.experiments.push_back(std::move(*o));
    if (group.size() > 1) {
        report.processes = std::to_string(group.size()) + " MPI processes, each experiment run whole on one:";
        for (int r = 0; r < group.size(); ++r) {
            report.processes += (r == 0 ? " " : "; ") + std::string("process ") + std::to_string(r) + ":";
            for (std::size_t i = 0; i < experiments.size(); ++i)
                if (owners[i] == r) report.processes += " " + experiments[i]->name();
        }
        report.processes += " (the machine above is process 0's; each experiment's results.json names its own)";
    }
    report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "finished in " << ProgressBar::formatDuration(report.wallSeconds) << std::endl;
    const CpuSample cpuAfter = currentCpuSample();
    const LoadAverage loadAfter = currentLoadAverage();
    report.loadAverageAfter = loadAfter.toString();
    report.othersCpuShare = othersCpuShare(cpuBefore, cpuAfter);
    report.busyWarning = busyMachineWarning(report.othersCpuShare, loadBefore, loadAfter, cpuAfter.cpus);
    out << "other processes used " << formatOthersShare(report.othersCpuShare) << " of the CPU time; load average "
        << loadBefore.toString() << " before, " << loadAfter.toString() << " after" << std::endl;
    if (!report.busyWarning.empty()) out << report.busyWarning << std::endl;
    if (wholeReport) {
        report.command = "raycache bench all";
        if (settings.size != BenchSize::Quick)
            report.command += " --" + toString(settings.size);
        else
            report.command += " --quick";
        if (options.threads > 0) report.command += " --threads " + std::to_string(options.threads);
        const std::filesystem::path path = settings.outDir / "report.md";
        writeTextFileAtomically(path, reportMarkdown(report));
        out << "wrote " << path.string() << std::endl;
    }
}

}  // namespace raycache
