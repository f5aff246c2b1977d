// lodestone-slam: offline graph SLAM on a rawlog or a simulated scenario.
#include <lodestone/slamapp/FrameAllocator.h>
#include <SlamApp.h>

#include <unistd.h>

#include <iostream>

int main(int argc, char** argv) {
    lodestone::slamapp::keepFrameBuffersMapped();
    return lodestone::slamapp::runSlamApp(argc, argv, std::cout, std::cerr, isatty(STDERR_FILENO));
}
