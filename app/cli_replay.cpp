// `faultline replay JOURNAL.jsonl [--data PATH...] [--out DIR] [--frames A:B | --shard K/N]`:
// runs a journal headless. Exit 0 only when every expectation holds; otherwise each failing line
// is named. --frames / --shard limit per-frame work (JOURNAL.md) so a run splits across machines.
#include "app/cli.hpp"

#include "core/io/input_error.hpp"
#include "core/session/journal.hpp"

#include <cstdio>
#include <stdexcept>

namespace faultline::app {

int runReplay(const Args& args) {
    std::string journal;
    core::ReplayOptions options;
    for (std::size_t k = 0; k < args.size(); ++k) {
        const std::string& a = args[k];
        if (a == "--data") {
            while (k + 1 < args.size() && args[k + 1].rfind("--", 0) != 0)
                options.data.push_back(args[++k]);
            if (options.data.empty()) {
                std::fprintf(stderr, "faultline replay: --data needs at least one path\n");
                return 2;
            }
        } else if (a == "--out" && k + 1 < args.size()) {
            options.outDir = args[++k];
        } else if ((a == "--frames" || a == "--shard") && k + 1 < args.size()) {
            try {
                const core::FrameSelection s = a == "--frames" ? core::parseFrameRange(args[++k])
                                                               : core::parseFrameShard(args[++k]);
                if (a == "--frames") {
                    options.frames.first = s.first;
                    options.frames.last = s.last;
                } else {
                    options.frames.shard = s.shard;
                    options.frames.shards = s.shards;
                }
            } catch (const std::invalid_argument& e) {
                std::fprintf(stderr, "faultline replay: %s\n", e.what());
                return 2;
            }
        } else if (a == "--strict") {
            options.strict = true;
        } else if (journal.empty() && a.rfind("--", 0) != 0) {
            journal = a;
        } else {
            std::fprintf(stderr, "faultline replay: unexpected argument '%s'\n", a.c_str());
            return 2;
        }
    }
    if (journal.empty()) {
        std::fprintf(stderr, "usage: faultline replay JOURNAL.jsonl [--data PATH...] [--out DIR] "
                             "[--frames A:B | --shard K/N] [--strict]\n");
        return 2;
    }
    core::Session session;
    registerAppOps(session);
    core::ReplayReport report;
    try {
        report = core::replayJournal(journal, options, session);
    } catch (const core::InputError& e) {
        std::fprintf(stderr, "faultline replay: %s\n", e.what());
        return 2;
    }
    for (const auto& w : report.warnings)
        std::fprintf(stderr, "%s:%zu: warning: %s (--strict makes this an error)\n",
                     journal.c_str(), w.line, w.message.c_str());
    for (const auto& f : report.failures)
        std::fprintf(stderr, "%s:%zu: %s\n", journal.c_str(), f.line, f.message.c_str());
    if (report.stopped)
        std::fprintf(stderr,
                     "faultline replay: stopped at the failing command; later lines did not run\n");
    std::printf("%s: %zu commands, %zu expectations, %zu failed%s\n", journal.c_str(),
                report.commands, report.expectations, report.failures.size(),
                options.frames.everything() ? ""
                                            : (" (" + options.frames.describe() + ")").c_str());
    return report.ok() ? 0 : 1;
}

} // namespace faultline::app
