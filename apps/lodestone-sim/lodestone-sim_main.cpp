// lodestone-sim: writes a simulated rawlog, its ground truth and kidnap events from a scenario.
#include <SimApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::sim::runSimApp(argc, argv, std::cout, std::cerr);
}
