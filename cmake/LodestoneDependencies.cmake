# Every third-party package the project uses, found once. Kept in one file so that the
# installed package config (lodestoneConfig.cmake.in) can re-find exactly the same set.
find_package(mrpt-obs REQUIRED)
find_package(mrpt-io REQUIRED)
find_package(mrpt-serialization REQUIRED)
find_package(mrpt-system REQUIRED)
find_package(mrpt-config REQUIRED)
find_package(mrpt-poses REQUIRED)
find_package(mrpt-img REQUIRED)
find_package(mrpt-tclap REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs features2d)
find_package(Eigen3 REQUIRED NO_MODULE)
find_package(nanoflann REQUIRED)
find_package(ZLIB REQUIRED)
