// File search for ResourceIndex: game paths against root folders, with a fallback that ignores
// case, and sorted recursive listings of decl folders.
//
// std::filesystem calls here always take an error_code: a folder that vanishes or cannot be read
// must give a diagnostic or "not found", never an exception out of the index.

#include "resource_index_impl.h"

#include "af/text/strings.h"

#include <algorithm>

namespace af {

std::optional<std::vector<std::string>> splitGamePath(std::string_view path) {
    std::vector<std::string> components;
    std::string current;
    auto flush = [&]() -> bool {
        if (current == "..") return false;
        if (!current.empty() && current != ".") components.push_back(current);
        current.clear();
        return true;
    };
    for (char c : path) {
        if (c == '/' || c == '\\') {
            if (!flush()) return std::nullopt;
        } else {
            current += c;
        }
    }
    if (!flush()) return std::nullopt;
    return components;
}

namespace {

bool isWanted(const fs::path& p, bool wantFolder) {
    std::error_code ec;
    return wantFolder ? fs::is_directory(p, ec) : fs::is_regular_file(p, ec);
}

bool descend(const fs::path& at, const std::vector<std::string>& components, std::size_t i, bool wantFolder,
             fs::path& out) {
    if (i == components.size()) {
        if (!isWanted(at, wantFolder)) return false;
        out = at;
        return true;
    }
    const std::string& name = components[i];
    std::error_code ec;
    // The exact spelling first: it is what Doom on Linux would open, and it costs no listing.
    if (const fs::path exact = at / name; fs::exists(exact, ec) && descend(exact, components, i + 1, wantFolder, out))
        return true;

    std::vector<fs::path> matches;
    fs::directory_iterator it(at, ec);
    for (const fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
        const std::string entry = it->path().filename().string();
        if (entry != name && equalsIgnoreCase(entry, name)) matches.push_back(it->path());
    }
    // Directory order is arbitrary; two spellings of one name must always resolve the same way.
    std::sort(matches.begin(), matches.end());
    for (const fs::path& match : matches)
        if (descend(match, components, i + 1, wantFolder, out)) return true;
    return false;
}

}  // namespace

std::optional<fs::path> findIgnoringCase(const fs::path& base, const std::vector<std::string>& components,
                                         bool wantFolder) {
    fs::path out;
    if (descend(base, components, 0, wantFolder, out)) return out;
    return std::nullopt;
}

std::vector<std::string> listFilesRecursively(const fs::path& folder, std::string_view extension,
                                              std::vector<Diagnostic>& diagnostics) {
    std::vector<std::string> files;
    std::error_code ec;
    fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
    for (const fs::recursive_directory_iterator end; !ec && it != end; it.increment(ec)) {
        std::error_code typeError;
        if (!it->is_regular_file(typeError)) continue;
        if (!equalsIgnoreCase(it->path().extension().string(), extension)) continue;
        files.push_back(it->path().lexically_relative(folder).generic_string());
    }
    if (ec)
        diagnostics.push_back({Severity::Warning, folder.string(), {},
                               "cannot list the folder (" + ec.message() + "); some files may be missing"});
    std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
        const std::string la = toLower(a), lb = toLower(b);
        return la != lb ? la < lb : a < b;
    });
    return files;
}

bool isAbsoluteGamePath(std::string_view path) {
    if (!path.empty() && (path.front() == '/' || path.front() == '\\')) return true;
    // A drive letter (`C:/x`, `c:x`): absolute on Windows, where most mods were made.
    return path.size() >= 2 && path[1] == ':' && ((path[0] | 0x20) >= 'a' && (path[0] | 0x20) <= 'z');
}

FileSearch ResourceIndex::Impl::findFile(std::string_view path) const {
    FileSearch search;
    // Mod folders are untrusted input: Doom's file system never opens a file outside its search
    // paths, so neither an absolute path nor a `..` is searched (docs/formats.md §1.1).
    if (isAbsoluteGamePath(path)) {
        search.problem = "the path is absolute, and files are only opened inside the root folders "
                         "(as Doom's file system opens them only inside its search paths)";
        return search;
    }
    const std::optional<std::vector<std::string>> components = splitGamePath(path);
    if (!components || components->empty()) {
        search.problem = components ? "the path is empty" : "the path leaves the root folder ('..')";
        return search;
    }
    fs::path relative;
    for (const std::string& c : *components) relative /= c;
    // Later roots override earlier ones, as a mod folder overrides base/.
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
        search.tried.push_back(*root / relative);
        if (std::optional<fs::path> found = findIgnoringCase(*root, *components, false)) {
            search.found = std::move(found);
            return search;
        }
    }
    return search;
}

std::string ResourceIndex::Impl::declFolders(std::string_view folder) const {
    std::string out;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
        if (!out.empty()) out += ", ";
        out += (*root / folder).string();
    }
    return out.empty() ? "(no root folders)" : out;
}

std::string ResourceIndex::Impl::topDeclFolder(std::string_view folder) const {
    return roots.empty() ? std::string(folder) : (roots.back() / folder).string();
}

}  // namespace af
