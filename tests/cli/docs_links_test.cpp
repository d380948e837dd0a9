// The documents stay true to the tree: every relative link of README.md and docs/*.md reaches a
// file (and its anchor), and every function README's lecture → code table names is in its file.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = LUZ_SOURCE_DIR;

/// The pages: README.md and every docs/*.md (notes included).
std::vector<fs::path> pages() {
    std::vector<fs::path> out{kRoot / "README.md"};
    for (const auto& e : fs::recursive_directory_iterator(kRoot / "docs")) {
        if (e.path().extension() == ".md") out.push_back(e.path());
    }
    return out;
}

/// GitHub's anchor of a heading: lower case, spaces to '-', ASCII punctuation other than '-'
/// and '_' dropped (other bytes kept).
std::string slug(const std::string& heading) {
    std::string s;
    for (const char c : heading) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x80 || std::isalnum(u) || c == '-' || c == '_') {
            s += static_cast<char>(u < 0x80 ? std::tolower(u) : u);
        } else if (c == ' ') {
            s += '-';
        }
    }
    return s;
}

/// The anchors a page defines: `<a id="…">` and its headings' slugs.
std::set<std::string> anchors(const std::string& text) {
    std::set<std::string> out;
    const std::regex id("<a id=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), id); it != std::sregex_iterator();
         ++it) {
        out.insert((*it)[1].str());
    }
    const std::regex heading("(^|\n)#+ ([^\n]+)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), heading);
         it != std::sregex_iterator(); ++it) {
        out.insert(slug((*it)[2].str()));
    }
    return out;
}

TEST(DocsLinks, EveryRelativeLinkReachesAFileAndItsAnchor) {
    int links = 0;
    std::map<fs::path, std::set<std::string>> defined;  // each page's anchors, read once
    for (const fs::path& page : pages()) {
        const std::string text = read_file(page);
        const std::regex link("\\]\\(([^()\\s]+)\\)|<img src=\"([^\"]+)\"");
        for (auto it = std::sregex_iterator(text.begin(), text.end(), link);
             it != std::sregex_iterator(); ++it) {
            const std::string target = (*it)[1].matched ? (*it)[1].str() : (*it)[2].str();
            if (target.rfind("http", 0) == 0 || target.rfind("mailto:", 0) == 0) continue;
            ++links;
            const size_t hash = target.find('#');
            const std::string file = target.substr(0, hash);
            const fs::path path = file.empty() ? page : page.parent_path() / file;
            ASSERT_TRUE(fs::exists(path)) << page << ": " << target << ": no such file";
            if (hash == std::string::npos) continue;
            const std::string anchor = target.substr(hash + 1);
            const fs::path key = fs::weakly_canonical(path);
            if (!defined.count(key)) defined[key] = anchors(read_file(path));
            EXPECT_TRUE(defined[key].count(anchor))
                << page << ": " << target << ": " << path.filename() << " has no #" << anchor;
        }
    }
    EXPECT_GT(links, 100);
}

TEST(DocsLinks, ReadmeLectureTableNamesFunctionsInTheirFiles) {
    const std::string text = read_file(kRoot / "README.md");
    const size_t start = text.find("## The lecture in the code");
    ASSERT_NE(start, std::string::npos);
    const std::string table = text.substr(start, text.find("\n## ", start + 3) - start);
    // `dir/file.ext`: `f()`, `g()` … ; the functions after a file are looked for in it
    const std::regex item("`([a-z_]+/[a-z_]+\\.(h|cpp))`|`([A-Za-z_:]+)(\\(\\))?`");
    fs::path file;
    int found = 0;
    for (auto it = std::sregex_iterator(table.begin(), table.end(), item);
         it != std::sregex_iterator(); ++it) {
        if ((*it)[1].matched) {
            file = kRoot / "src" / (*it)[1].str();
            ASSERT_TRUE(fs::exists(file)) << file;
            continue;
        }
        const std::string name = (*it)[3].str();
        if (file.empty() || (!(*it)[4].matched && name != "TreeRules")) continue;
        // Class::member(): the class and "member(" (defined in the class or as Class<W>::);
        // function(): "function("; a type: "struct Type"
        const std::string source = read_file(file);
        const size_t colons = name.rfind("::");
        if (colons != std::string::npos) {
            EXPECT_NE(source.find(name.substr(0, colons)), std::string::npos) << name << file;
            EXPECT_NE(source.find(name.substr(colons + 2) + "("), std::string::npos)
                << name << " not in " << file;
        } else {
            const std::string definition = (*it)[4].matched ? name + "(" : "struct " + name;
            EXPECT_NE(source.find(definition), std::string::npos) << name << " not in " << file;
        }
        ++found;
    }
    EXPECT_GE(found, 20);
}

}  // namespace
}  // namespace luz::test
