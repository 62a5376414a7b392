#include "app/BenchCommand.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <ostream>

#include "bench/ExperimentRegistry.h"
#include "bench/MachineLoad.h"
#include "bench/Report.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/Parallel.h"

namespace raycache {

void runBenchCommand(const BenchCommandOptions& options, std::ostream& out) {
    if (options.list) {
        for (const auto& e : allExperiments()) out << e->name() << "  " << e->title() << "\n";
        return;
    }
    if (static_cast<int>(options.quick) + static_cast<int>(options.full) + static_cast<int>(options.tiny) > 1)
        throw InputError("choose one of --quick, --full and --tiny");
    if (options.threads < 0 || options.threads > 1024) throw InputError("--threads must be between 0 (all) and 1024");
    if (options.outDir.empty()) throw InputError("--out must name a directory");
    const auto experiments = selectExperiments(options.experiments);
    const bool wholeReport =
        std::find(options.experiments.begin(), options.experiments.end(), "all") != options.experiments.end();

    BenchSettings settings;
    settings.size = options.full ? BenchSize::Full : options.tiny ? BenchSize::Tiny : BenchSize::Quick;
    settings.threads = options.threads;
    settings.outDir = options.outDir;
    std::error_code ec;
    std::filesystem::create_directories(settings.outDir, ec);
    if (ec || !std::filesystem::is_directory(settings.outDir))
        throw RuntimeError("cannot create the results directory " + settings.outDir.string() + ": " + ec.message());

    const Parallel parallel(settings.threads);
    const LoadAverage loadBefore = currentLoadAverage();
    const CpuSample cpuBefore = currentCpuSample();
    const RunEnvironment environment = currentRunEnvironment(parallel.threadCount());
    double totalWork = 0.0;
    for (const auto& e : experiments) totalWork += e->estimatedWork(settings);

    out << "raycache bench: " << experiments.size() << " experiment" << (experiments.size() == 1 ? "" : "s") << ", "
        << toString(settings.size) << " size, " << parallel.threadCount() << " threads, results in "
        << settings.outDir.string() << "/" << std::endl;
    ProgressBar progress(out, options.interactive, totalWork);
    const auto start = std::chrono::steady_clock::now();
    ReportInput report{.settings = settings, .environment = environment};
    for (const auto& e : experiments) {
        ExperimentContext context{settings, parallel, progress, environment, settings.outDir / e->name()};
        std::filesystem::create_directories(context.dir, ec);
        if (ec) throw RuntimeError("cannot create " + context.dir.string() + ": " + ec.message());
        ExperimentOutput output = e->run(context);
        progress.note(output.title);
        for (const std::string& c : output.caveats) progress.note("  note: " + c);
        for (const std::string& h : output.headlines) progress.note("  " + h);
        progress.note("  wrote " + (context.dir / "results.md").string());
        report.experiments.push_back(std::move(output));
    }
    progress.finish();
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
