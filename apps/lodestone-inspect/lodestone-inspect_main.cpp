// lodestone-inspect: RawLogViewer-style inspection of rawlogs on the command line.
#include <InspectApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::inspect::runInspectApp(argc, argv, std::cout, std::cerr);
}
