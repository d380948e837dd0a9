// `luz render --help` and `luz view --help` against the reference pages: every option the help
// lists is in the page's options table and every option of the table is in the help.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

class HelpDocs : public TempDirTest {};

/// The `--long` option names in `text` (word characters and dashes after two dashes).
std::set<std::string> long_options(const std::string& text) {
    std::set<std::string> names;
    const std::regex option("(^|[^-\\w])(--[a-z][a-z-]*)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option);
         it != std::sregex_iterator(); ++it) {
        names.insert((*it)[2].str());
    }
    return names;
}

/// The table of the section starting at `heading` in `page` (docs/), its rows' first cells.
std::string option_column(const std::string& page, const std::string& heading) {
    const std::string text = read_file(std::filesystem::path(LUZ_SOURCE_DIR) / "docs" / page);
    const size_t start = text.find(heading);
    EXPECT_NE(start, std::string::npos) << page << " has no " << heading;
    if (start == std::string::npos) return "";
    const size_t end = text.find("\n## ", start + heading.size());
    std::string cells;
    size_t line = start;
    while (line < end && line != std::string::npos) {
        const size_t eol = text.find('\n', line);
        const std::string row = text.substr(line, eol == std::string::npos ? eol : eol - line);
        if (row.rfind("| `", 0) == 0) cells += row.substr(0, row.find(" | ", 2)) + "\n";
        line = eol == std::string::npos ? eol : eol + 1;
    }
    return cells;
}

std::set<std::string> without_help(std::set<std::string> names) {
    names.erase("--help");
    return names;
}

TEST_F(HelpDocs, RenderHelpAndCliPageListTheSameOptions) {
    const RunResult r = run_luz({"render", "--help"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    // the options' lines, not the footer after them (which names --checkpoint again)
    const std::set<std::string> help =
        without_help(long_options(r.out.substr(0, r.out.find("\nExit status"))));
    const std::set<std::string> page = long_options(option_column("CLI.md", "## `render` options"));
    EXPECT_GE(help.size(), 19u);
    EXPECT_EQ(help, page) << "luz render --help and docs/CLI.md's table of options differ";
}

TEST_F(HelpDocs, ViewHelpAndViewerPageListTheSameOptions) {
    const RunResult r = run_luz({"view", "--help"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::set<std::string> help = without_help(long_options(r.out));
    const std::set<std::string> page = long_options(option_column("VIEWER.md", "## Options"));
    EXPECT_GE(help.size(), 8u);
    EXPECT_EQ(help, page) << "luz view --help and docs/VIEWER.md's table of options differ";
}

TEST_F(HelpDocs, RenderHelpGivesExitStatusesEnvironmentAndTheManual) {
    const RunResult r = run_luz({"render", "--help"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* text : {"Exit status: 0 success; 2 bad input", "1 any other failure",
                             "LUZ_CHECKPOINT_SECONDS", "docs/CLI.md", "docs/SCENES.md"}) {
        EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
    }
}

}  // namespace
}  // namespace luz::test
