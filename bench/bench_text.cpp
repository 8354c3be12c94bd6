// Throughput of the text stage: tokenizing and parsing .af text, in bytes per second.
// The input is our humanoid figure repeated to about 4 MB, so caches do not flatter the lexer.

#include "af/text/af_parser.h"
#include "af/text/lexer.h"

#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string readSample() {
    std::ifstream in(std::string(AF_SOURCE_DIR) + "/af/humanoid.af", std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Copies of the figure under different names: a valid file of many decls.
const std::string& corpus() {
    static const std::string text = [] {
        const std::string one = readSample();
        const std::string header = "articulatedFigure humanoid {";
        std::string all;
        for (int i = 0; all.size() < (4u << 20); ++i) {
            std::string copy = one;
            if (const std::size_t at = copy.find(header); at != std::string::npos)
                copy.replace(at, header.size(), "articulatedFigure humanoid_" + std::to_string(i) + " {");
            all += copy;
        }
        return all;
    }();
    return text;
}

void BM_Tokenize(benchmark::State& state) {
    const std::string& text = corpus();
    std::size_t tokens = 0;
    for (auto _ : state) {
        af::Diagnostics diagnostics;
        af::Lexer lexer(text, diagnostics);
        for (af::Token t = lexer.next(); t.type != af::TokenType::End; t = lexer.next()) ++tokens;
        benchmark::DoNotOptimize(tokens);
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}
BENCHMARK(BM_Tokenize)->Unit(benchmark::kMillisecond);

void BM_ParseAF(benchmark::State& state) {
    const std::string& text = corpus();
    for (auto _ : state) {
        af::AFParseResult r = af::parseAF(text, "bench.af");
        if (!r.ok()) state.SkipWithError("the benchmark corpus does not parse");
        benchmark::DoNotOptimize(r.file.decls.data());
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}
BENCHMARK(BM_ParseAF)->Unit(benchmark::kMillisecond);

}  // namespace
