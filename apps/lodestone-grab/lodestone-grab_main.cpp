// lodestone-grab: live sensors into a rawlog (rawlog-grabber's INI, written safely).
#include <GrabApp.h>

#include <iostream>

#include <unistd.h>

int main(int argc, char** argv) {
    return lodestone::grab::runGrabApp(argc, argv, std::cout, std::cerr, ::isatty(STDERR_FILENO) != 0);
}
