// Writes the bundled sample rawlog (rawlogs/sample_drive.rawlog.gz): the deterministic drive of
// tests/support/SampleObservations. Kept so the file can be remade and checked:
//   make_sample_rawlog rawlogs/sample_drive.rawlog.gz
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/obs/registerAllClasses.h>

#include <iostream>

#include "SampleObservations.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: make_sample_rawlog OUT.rawlog[.gz]\n";
        return 2;
    }
    lodestone::registerAllClasses();
    const std::string out = argv[1];
    const bool gz = out.size() > 3 && out.compare(out.size() - 3, 3, ".gz") == 0;
    try {
        lodestone::io::RawlogWriter writer(out, {gz ? 9 : 0});
        for (const auto& obs : lodestone::test::makeSampleDrive({})) writer.write(*obs);
        writer.close();
        std::cout << writer.entriesWritten() << " entries -> " << out << "\n";
    } catch (const std::exception& e) {
        std::cerr << "make_sample_rawlog: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
