// lodestone-magfit: fit MagneticGpERD's GP hyperparameters to a recording.
#include <MagneticFitApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::slamapp::runMagneticFitApp(argc, argv, std::cout, std::cerr);
}
