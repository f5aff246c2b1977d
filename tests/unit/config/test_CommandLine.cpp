#include <gtest/gtest.h>
#include <lodestone/config/CommandLine.h>

using lodestone::config::ParseOutcome;
using lodestone::config::parseCommandLine;

namespace {
ParseOutcome parse(const std::vector<std::string>& words) {
    TCLAP::CmdLine cmd("test", ' ', "");
    TCLAP::ValueArg<double> step("", "step", "a number", false, 1.0, "M", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no output", cmd);
    TCLAP::UnlabeledMultiArg<std::string> positional("FILES", "files", false, "FILE", cmd);
    return parseCommandLine(cmd, words);
}
}  // namespace

TEST(CommandLine, AnUnknownOptionIsNamedNotTakenForAFile) {
    // A positional multi-argument would swallow "--bogus"; the user must hear of the option.
    auto r = parse({"app", "--bogus", "a", "b"});
    EXPECT_EQ(r.kind, ParseOutcome::Kind::UsageError);
    EXPECT_NE(r.error.find("'--bogus'"), std::string::npos) << r.error;
    r = parse({"app", "a", "-z"});
    EXPECT_EQ(r.kind, ParseOutcome::Kind::UsageError);
    EXPECT_NE(r.error.find("'-z'"), std::string::npos) << r.error;
}

TEST(CommandLine, KnownOptionsNegativeNumbersAndWordsAfterDoubleDashPass) {
    EXPECT_EQ(parse({"app", "--step", "-0.5", "-q", "a", "b"}).kind, ParseOutcome::Kind::Run);
    EXPECT_EQ(parse({"app", "--quiet", "--step", "-.5", "a"}).kind, ParseOutcome::Kind::Run);
    EXPECT_EQ(parse({"app", "--", "-file-with-a-dash"}).kind, ParseOutcome::Kind::Run);
    EXPECT_EQ(parse({"app", "-qq", "a"}).kind, ParseOutcome::Kind::Run);  // switches run together
    EXPECT_EQ(parse({"app", "-qz", "a"}).kind, ParseOutcome::Kind::UsageError);
}

TEST(CommandLine, AMissingRequiredArgumentReadsCleanly) {
    TCLAP::CmdLine cmd("test", ' ', "");
    TCLAP::UnlabeledValueArg<std::string> file("FILE", "a file", true, "", "FILE", cmd);
    TCLAP::ValueArg<double> step("", "step", "a number", false, 1.0, "M", cmd);
    auto r = parseCommandLine(cmd, {"app"});
    EXPECT_EQ(r.kind, ParseOutcome::Kind::UsageError);
    // Not " : One or more ..." (TCLAP's argument id of such an error is a blank).
    EXPECT_EQ(r.error.rfind("One or more required arguments missing", 0), 0u) << r.error;
}
