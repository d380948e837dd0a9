// The `luz` command line: parses it (CLI11) and maps outcomes to exit statuses: 0 success,
// 2 bad input (one line on standard error), 1 any other failure (docs/CLI.md). Shared by `luz`
// (app/main.cpp) and, on rank 0, by `luz-mpi` (src/mpi/), which renders frames its own way.
#include "app/cli_main.h"

#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "app/cli_options.h"
#include "app/figures_command.h"
#include "app/list_commands.h"
#include "app/signals.h"
#include "app/standard_output.h"
#include "app/view_command.h"
#include "app/web_command.h"
#include "luz/luz.h"

#ifndef LUZ_VERSION
#define LUZ_VERSION "0.0.0"
#endif

namespace luz {
void print_error_line(const std::string& message) {
    std::string line = luz::one_line(message);
    line += '\n';
    std::fwrite(line.data(), 1, line.size(), stderr);
}

namespace {

int run(int argc, char** argv, const FrameRenderer* render_frame) {
    CLI::App app{
        "luz renders 3D scenes with the classic illumination models (ambient, Lambert, "
        "Phong) through a z-buffer rasterizer or a ray tracer.",
        "luz"};
    app.set_version_flag("--version", std::string("luz ") + LUZ_VERSION);
    app.require_subcommand(1);

    luz::RenderArgs render_options;
    CLI::App* render = app.add_subcommand("render", "render a scene to an image file");
    luz::add_render_options(*render, render_options);

    CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes (demo:NAME)");
    CLI::App* materials = app.add_subcommand("materials", "list the material presets");
    luz::ViewOptions view_options;
    CLI::App* view = app.add_subcommand("view", "interactive window: edit the scene live");
    luz::add_view_options(*view, view_options);
    luz::FiguresOptions figures_options;
    CLI::App* figures = app.add_subcommand(
        "figures",
        "regenerate the lecture's figures and the SPD gallery into a folder with index.html");
    luz::add_figures_options(*figures, figures_options);
    luz::WebOptions web_options;
    CLI::App* web = app.add_subcommand("web", "write luz.html: luz in a web page, offline");
    luz::add_web_options(*web, web_options);

    // CLI11 would only say "A subcommand is required" for a misspelt command
    const auto is_command = [&](const std::string& name) {
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
            if (sub->get_name() == name) return true;
        }
        return false;
    };
    if (argc > 1 && argv[1][0] != '-' && !is_command(argv[1])) {
        print_error_line(
            std::string("luz: unknown command \"") + argv[1] +
            "\" (expected render, view, figures, web, scenes or materials; see luz --help)");
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        print_error_line(std::string("luz: ") + e.what());
        return 2;
    }

    if (*scenes) {
        luz::print_scenes(stdout);
        return 0;
    }
    if (*materials) {
        luz::print_materials(stdout);
        return 0;
    }
    if (*view) return luz::run_view(view_options);
    if (*figures) return luz::run_figures(figures_options);
    if (*web) return luz::run_web(web_options);
    return render_frame ? luz::run_render(render_options, *render_frame)
                        : luz::run_render(render_options);
}

/// run() with its failures turned into messages and exit statuses.
int run_reporting_failures(int argc, char** argv, const FrameRenderer* render_frame) {
    // The signal flag also stops loads, builds and encodings at their next check (Cancelled).
    const CancelScope cancel(&interrupt_flag());
    try {
        return run(argc, argv, render_frame);
    } catch (const luz::Interrupted& e) {
        print_error_line("luz: interrupted");  // nothing written (app/signals.h)
        return 128 + e.signal;
    } catch (const luz::Cancelled&) {
        print_error_line("luz: interrupted");  // the temporary files went with their owners
        return 128 + (interrupt_signal() != 0 ? interrupt_signal() : SIGINT);
    } catch (const luz::InputError& e) {
        print_error_line(e.what());  // already names the file and the place
        return 2;
    } catch (const std::exception& e) {
        print_error_line(std::string("luz: ") + e.what());
        return 1;
    } catch (...) {
        print_error_line("luz: unexpected failure");
        return 1;
    }
}

}  // namespace

int luz_main(int argc, char** argv, const FrameRenderer* render_frame) {
    catch_sigpipe();
    return finish_standard_output(run_reporting_failures(argc, argv, render_frame));
}

}  // namespace luz
