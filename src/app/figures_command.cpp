// `luz figures`: checks DIR (new, empty, or a folder luz figures made: it holds .luz-figures),
// finds the figures program (installed copy under share/luz/figures/ or the source tree's
// src/figures/), runs Debian's python3 on it into a temporary folder next to DIR, and renames
// that folder into place only when it succeeded.
#include "app/figures_command.h"

#include <stdlib.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "app/child_process.h"

#ifndef LUZ_FIGURES_SOURCE_DIR
#define LUZ_FIGURES_SOURCE_DIR ""
#endif
#ifndef LUZ_SCENES_SOURCE_DIR
#define LUZ_SCENES_SOURCE_DIR ""
#endif

namespace fs = std::filesystem;

namespace luz {
namespace {

constexpr const char* kPython = "/usr/bin/python3";  // Debian's, with python3-matplotlib

/// The file that marks a folder as made by luz figures: only such a folder (or an empty one) is
/// ever replaced.
constexpr const char* kMarker = ".luz-figures";
constexpr const char* kMarkerText =
    "This folder was made by `luz figures`: the next `luz figures -o` into it replaces it "
    "whole.\n";

/// Where the figures program and its scenes are: {script, scenes root}, or empty paths.
struct FiguresFiles {
    fs::path script, scenes;
};

/// The running executable (/proc/self/exe).
fs::path self_exe() {
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe;
}

/// Prefers the copy installed beside the binary (PREFIX/share/luz/), then the source tree.
FiguresFiles find_figures_files(const fs::path& exe) {
    const fs::path share = exe.parent_path().parent_path() / "share" / "luz";
    if (fs::exists(share / "figures" / "luz_figures.py") && fs::exists(share / "scenes"))
        return {share / "figures" / "luz_figures.py", share / "scenes"};
    const fs::path src = fs::path(LUZ_FIGURES_SOURCE_DIR) / "luz_figures.py";
    if (!std::string(LUZ_FIGURES_SOURCE_DIR).empty() && fs::exists(src))
        return {src, fs::path(LUZ_SCENES_SOURCE_DIR)};
    return {};
}

/// Prints "luz figures: MESSAGE" as one line and returns `code`.
int fail(int code, const std::string& message) {
    std::fprintf(stderr, "luz figures: %s\n", message.c_str());
    return code;
}

/// Whether the folder `dir` may be replaced: it is empty or luz figures made it.
bool replaceable(const fs::path& dir) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(dir / kMarker, ec))) return true;
    return fs::is_empty(dir, ec) && !ec;
}

/// The message for a folder luz will not replace.
std::string not_ours(const std::string& out) {
    return out + " exists and is not a luz figures folder (it has no " + kMarker +
           " file): choose another -o, or remove it first";
}

/// Writes the marker into the new folder `dir`; false on failure (errno set).
bool write_marker(const fs::path& dir) {
    std::FILE* f = std::fopen((dir / kMarker).c_str(), "wx");
    if (f == nullptr) return false;
    const bool ok = std::fputs(kMarkerText, f) >= 0;
    return std::fclose(f) == 0 && ok;
}

}  // namespace

void add_figures_options(CLI::App& cmd, FiguresOptions& o) {
    cmd.add_option("-o,--output", o.out,
                   "folder to write the figures and index.html into (default: figures); an "
                   "existing one is replaced once every figure is made, only if luz figures "
                   "made it (or it is empty)")
        ->type_name("DIR");
}

int run_figures(const FiguresOptions& o) {
    if (o.out.empty()) return fail(2, "-o: empty folder name");
    fs::path dir = fs::absolute(fs::path(o.out)).lexically_normal();
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(dir, ec);
    if (fs::exists(st) && !fs::is_directory(fs::status(dir, ec)))
        return fail(2, "-o " + o.out + ": exists and is not a folder");
    if (fs::exists(st)) {
        if (!replaceable(dir)) return fail(2, not_ours(o.out));
        dir = fs::canonical(dir, ec);  // a symbolic link: its folder is replaced, not the link
        if (ec) return fail(1, "-o " + o.out + ": " + ec.message());
    }
    fs::path name = dir.filename();
    fs::path parent = dir.parent_path();
    if (name.empty() || name == "." || name == "..")
        return fail(2, "-o " + o.out + ": name a folder to create or replace");
    if (!fs::is_directory(parent, ec))
        return fail(2, "-o " + o.out + ": the folder " + parent.string() + " does not exist");
    if (access(parent.c_str(), W_OK | X_OK) != 0)
        return fail(
            1, "-o " + o.out + ": cannot write in " + parent.string() + " (permission denied)");

    // The program, its scenes and the interpreter
    const fs::path exe = self_exe();
    const FiguresFiles files = find_figures_files(exe);
    if (files.script.empty())
        return fail(1, "cannot find the figures program (share/luz/figures/luz_figures.py)");
    const char* python_env = std::getenv("LUZ_FIGURES_PYTHON");  // tests: another interpreter
    const std::string python = python_env && *python_env ? python_env : kPython;
    if (access(python.c_str(), X_OK) != 0)
        return fail(1, python +
                           " not found: install Debian's python3-matplotlib (apt-get "
                           "install python3-matplotlib python3-numpy)");

    // Everything goes into a temporary folder next to DIR, renamed into place at the end
    std::string tmpl = (parent / ("." + name.string() + ".tmp-XXXXXX")).string();
    if (mkdtemp(tmpl.data()) == nullptr)
        return fail(1, "cannot create a temporary folder in " + parent.string() + ": " +
                           std::strerror(errno));
    const fs::path tmp = tmpl;
    const ChildResult child = run_child({python, files.script.string(), "--luz", exe.string(),
                                         "--scenes", files.scenes.string(), "--out", tmp.string()});
    if (child.status != 0 || child.stopped != 0) {
        fs::remove_all(tmp, ec);
        if (child.stopped != 0) return fail(128 + child.stopped, "interrupted");
        if (child.status == 127) return fail(1, "could not run " + python);
        if (child.status >= 128) return child.status;  // killed from elsewhere
        return fail(1, "not every figure could be made; " + o.out + " left as it was");
    }
    if (stop_signal() != 0) {  // a signal since the program ended: nothing replaced yet
        fs::remove_all(tmp, ec);
        return fail(128 + stop_signal(), "interrupted");
    }
    if (!write_marker(tmp)) {
        const std::string why = std::strerror(errno);
        fs::remove_all(tmp, ec);
        return fail(1, "cannot write " + (tmp / kMarker).string() + ": " + why);
    }
    // DIR may have appeared while the figures were made
    if (fs::exists(fs::symlink_status(dir, ec)) &&
        (!fs::is_directory(fs::symlink_status(dir, ec)) || !replaceable(dir))) {
        fs::remove_all(tmp, ec);
        return fail(2, not_ours(o.out));
    }
    fs::permissions(tmp,
                    fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                        fs::perms::others_read | fs::perms::others_exec,
                    ec);
    if (fs::exists(dir)) {
        // The old folder moves aside first, so DIR is always either the old or the new one
        std::string old_tmpl = (parent / ("." + name.string() + ".old-XXXXXX")).string();
        if (mkdtemp(old_tmpl.data()) == nullptr || rename(dir.c_str(), old_tmpl.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            fs::remove_all(tmp, ec);
            fs::remove(old_tmpl, ec);
            return fail(1, "cannot replace " + o.out + ": " + why);
        }
        if (rename(tmp.c_str(), dir.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            rename(old_tmpl.c_str(), dir.c_str());
            fs::remove_all(tmp, ec);
            return fail(1, "cannot rename the new figures into " + o.out + ": " + why);
        }
        fs::remove_all(old_tmpl, ec);
    } else if (rename(tmp.c_str(), dir.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        fs::remove_all(tmp, ec);
        return fail(1, "cannot rename the new figures into " + o.out + ": " + why);
    }
    std::printf("luz figures: wrote %s/index.html\n", o.out.c_str());
    return 0;
}

}  // namespace luz
