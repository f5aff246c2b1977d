// lodestone-import: datasets (TUM RGB-D, ...) into rawlogs.
#include <lodestone/io/ImportApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::io::runImportApp(argc, argv, std::cout, std::cerr);
}
