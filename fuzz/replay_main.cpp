// Runs a fuzz target without libFuzzer: every seed file as it is, then deterministic mutations
// of it (truncations, byte flips, inserted punctuation), so the normal test run and the
// sanitizer build exercise the parsers on broken input too.
//
// usage: replay [--mutations N] FILE_OR_DIR...

#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void run(const std::string& bytes) {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

std::string mutate(const std::string& seed, std::mt19937& rng) {
    static const char kInteresting[] = "{}(),-\"'/*\\\n\r\0.#e9";
    std::string s = seed;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !s.empty(); ++e) {
        const std::size_t at = rng() % s.size();
        switch (rng() % 4) {
        case 0: s.resize(at); break;
        case 1: s[at] = static_cast<char>(rng() & 0xff); break;
        case 2: s.insert(at, 1, kInteresting[rng() % (sizeof kInteresting - 1)]); break;
        case 3: s.erase(at, 1 + rng() % 16); break;
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    int mutations = 200;
    std::vector<std::filesystem::path> seeds;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--mutations" && i + 1 < argc) {
            mutations = std::atoi(argv[++i]);
        } else if (std::filesystem::is_directory(arg)) {
            for (const auto& e : std::filesystem::directory_iterator(arg))
                if (e.is_regular_file()) seeds.push_back(e.path());
        } else {
            seeds.emplace_back(arg);
        }
    }
    std::sort(seeds.begin(), seeds.end());
    std::mt19937 rng(20261122);
    std::size_t runs = 0;
    for (const auto& path : seeds) {
        std::ifstream in(path, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        run(text.str());
        for (int m = 0; m < mutations; ++m) run(mutate(text.str(), rng));
        runs += 1 + static_cast<std::size_t>(mutations);
    }
    std::printf("replayed %zu inputs from %zu seeds\n", runs, seeds.size());
    return seeds.empty() ? 1 : 0;
}
