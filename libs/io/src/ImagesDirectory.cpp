#include <lodestone/io/ImagesDirectory.h>
#include <lodestone/io/RawlogPaths.h>

#include <filesystem>

namespace lodestone::io {

namespace fs = std::filesystem;

std::string findImagesDirectory(const std::string& rawlogPath) {
    const fs::path path(rawlogPath);
    const std::string base = rawlogStem(path.filename().string());
    const fs::path dir = path.parent_path();
    const fs::path candidates[] = {dir / (base + "_Images"), dir / (base + "_images"),
                                   dir / (base + "_IMAGES"), dir / "Images"};
    for (const auto& c : candidates) {
        std::error_code ec;
        if (fs::is_directory(c, ec)) return c.string();
    }
    return candidates[0].string();
}

}  // namespace lodestone::io
