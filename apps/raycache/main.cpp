// raycache command line: parses arguments and hands them to the library.
#include <CLI/CLI.hpp>
#include <iostream>

#include "app/RenderCommand.h"
#include "app/ScenesCommand.h"
#include "core/Errors.h"

int main(int argc, char** argv) {
    CLI::App app{"raycache: real-time Whitted ray tracing with per-object ray caching"};
    app.require_subcommand(1);

    raycache::RenderCommandOptions render;
    CLI::App* renderCmd = app.add_subcommand("render", "Render a scene along its camera path");
    renderCmd->add_option("--scene", render.scene, "Built-in scene name (see `raycache scenes`) or scene .json file")
        ->capture_default_str();
    renderCmd->add_option("--width", render.width, "Image width in pixels")->capture_default_str();
    renderCmd->add_option("--height", render.height, "Image height in pixels")->capture_default_str();
    renderCmd->add_option("--frames", render.frames, "Frames to render (default: the scene's path length)");
    renderCmd->add_option("--path", render.path, "Camera path: static, orbit or pan (default: the scene's own)");
    renderCmd->add_option("--threads", render.threads, "Worker threads, 0 = all cores")->capture_default_str();
    renderCmd->add_option("--max-depth", render.maxDepth, "Longest ray path (primary ray = 1)")->capture_default_str();
    renderCmd->add_option("--min-weight", render.minWeight, "Stop a path when its kr/kt product falls below this")
        ->capture_default_str();
    renderCmd->add_option("--technique", render.technique,
                          "Secondary-ray caching for every mirror/glass object: none or cct "
                          "(default: each material's own setting)");
    renderCmd->add_option("--cache-res", render.cacheResolution, "Caching-cube face resolution, 16..2048 "
                                                                 "(default: each material's own, 512 in built-in scenes)");
    renderCmd->add_flag("--cache-ideal", render.cacheIdeal,
                        "Benchmark switch: cache misses return black instead of being traced");
    renderCmd->add_option("--out", render.out,
                          "Image to write (.png sRGB 8-bit, .exr linear float); %04d in the name writes every frame");
    renderCmd->add_option("--stats", render.statsPath, "Write per-frame statistics as JSON to this file");

    app.add_subcommand("scenes", "List the built-in scenes, one per line");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }

    try {
        if (renderCmd->parsed()) raycache::runRenderCommand(render, std::cout);
        else raycache::runScenesCommand(std::cout);
    } catch (const raycache::InputError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
