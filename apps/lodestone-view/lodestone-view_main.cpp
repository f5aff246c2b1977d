// lodestone-view: the 3D scene of a finished run or a saved map.
#include <ViewApp.h>

#include <iostream>

int main(int argc, char** argv) { return lodestone::view::runViewApp(argc, argv, std::cout, std::cerr); }
