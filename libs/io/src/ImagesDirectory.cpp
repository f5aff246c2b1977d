#include <lodestone/io/ImagesDirectory.h>

#include <filesystem>

namespace lodestone::io {

namespace fs = std::filesystem;

std::string findImagesDirectory(const std::string& rawlogPath) {
    const fs::path path(rawlogPath);
    std::string base = path.filename().string();
    for (const std::string ext : {".gz", ".rawlog"}) {
        if (base.size() > ext.size() &&
            base.compare(base.size() - ext.size(), ext.size(), ext) == 0) {
            base.resize(base.size() - ext.size());
        }
    }
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
