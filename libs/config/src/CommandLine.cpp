#include <lodestone/config/CommandLine.h>

#include <memory>

namespace lodestone::config {

namespace {
class RecordingOutput : public TCLAP::StdOutput {
  public:
    void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override {
        error = e.argId() + ": " + e.error();
    }
    std::string error;
};
}  // namespace

ParseOutcome parseCommandLine(TCLAP::CmdLine& cmd, const std::vector<std::string>& words) {
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
