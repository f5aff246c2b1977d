#include <lodestone/config/CommandLine.h>

#include <algorithm>
#include <cctype>
#include <memory>

namespace lodestone::config {

namespace {
class RecordingOutput : public TCLAP::StdOutput {
  public:
    void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override {
        // TCLAP's argId is " " for errors of no one argument (a required one missing).
        std::string id = e.argId();
        id.erase(0, id.find_first_not_of(' '));
        id.erase(id.find_last_not_of(' ') + 1);
        error = id.empty() ? e.error() : id + ": " + e.error();
    }
    std::string error;
};
/** A word that looks like an option no argument of `cmd` has (`--bogus`, `-z`): TCLAP lets a
 * positional multi-argument swallow it, and the user would then read "expected DIR and OUT".
 * Numbers (`-1`, `-.5`, `-1e3`) are values, not options. */
std::string unknownOption(TCLAP::CmdLine& cmd, const std::vector<std::string>& words) {
    for (std::size_t i = 1; i < words.size(); ++i) {
        const std::string& w = words[i];
        if (w == "--") break;  // everything after it is positional
        if (w.size() < 2 || w[0] != '-') continue;
        if (std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '.') continue;
        const bool longForm = w[1] == '-';
        const std::string name = w.substr(longForm ? 2 : 1, w.find('=') == std::string::npos
                                                                 ? std::string::npos
                                                                 : w.find('=') - (longForm ? 2 : 1));
        const auto isKnown = [&](const std::string& n, bool asLong) {
            for (TCLAP::Arg* a : cmd.getArgList()) {
                if (asLong ? a->getName() == n : a->getFlag() == n) return true;
            }
            return false;
        };
        // TCLAP also takes short switches run together ("-qv"): each letter a known flag.
        bool known = isKnown(name, longForm);
        if (!known && !longForm && name.size() > 1) {
            known = std::all_of(name.begin(), name.end(),
                                [&](char c) { return isKnown(std::string(1, c), false); });
        }
        if (!known) return w;
    }
    return {};
}
}  // namespace

ParseOutcome parseCommandLine(TCLAP::CmdLine& cmd, const std::vector<std::string>& words) {
    if (const auto unknown = unknownOption(cmd, words); !unknown.empty()) {
        return {ParseOutcome::Kind::UsageError, "unknown option '" + unknown + "'"};
    }
    std::vector<const char*> argv;
    for (const auto& w : words) argv.push_back(w.c_str());
    RecordingOutput output;
    // setOutput() makes the caller the owner of outputs: free TCLAP's built-in one.
    std::unique_ptr<TCLAP::CmdLineOutput> builtin(cmd.getOutput());
    cmd.setOutput(&output);
    const bool ok = cmd.parse(static_cast<int>(argv.size()), argv.data());
    cmd.setOutput(nullptr);
    if (!output.error.empty()) return {ParseOutcome::Kind::UsageError, output.error};
    return {ok ? ParseOutcome::Kind::Run : ParseOutcome::Kind::HelpShown, {}};
}

}  // namespace lodestone::config
