// lodestone-import: datasets (TUM RGB-D, ...) into rawlogs.
#include <ImportApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::datasets::runImportApp(argc, argv, std::cout, std::cerr);
}
