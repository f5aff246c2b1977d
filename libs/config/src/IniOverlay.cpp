#include <lodestone/config/IniOverlay.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace lodestone::config {

IniOverlay::IniOverlay(const mrpt::config::CConfigFileBase& base, std::string sourceName)
    : base_(base), name_(std::move(sourceName)) {}

void IniOverlay::set(const std::string& section, const std::string& key, const std::string& value) {
    values_[{section, key}] = value;
}

void IniOverlay::set(const std::string& section, const std::string& key, double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);  // 17 digits: the same double back
    set(section, key, std::string(text));
}

void IniOverlay::getAllSections(std::vector<std::string>& sections) const {
    base_.getAllSections(sections);
    for (const auto& [at, value] : values_) {
        if (std::find(sections.begin(), sections.end(), at.first) == sections.end()) {
            sections.push_back(at.first);
        }
    }
}

void IniOverlay::getAllKeys(const std::string& section, std::vector<std::string>& keys) const {
    base_.getAllKeys(section, keys);
    for (const auto& [at, value] : values_) {
        if (at.first == section && std::find(keys.begin(), keys.end(), at.second) == keys.end()) {
            keys.push_back(at.second);
        }
    }
}

void IniOverlay::clear() { throw std::logic_error(name_ + ": an INI overlay cannot be cleared"); }

void IniOverlay::writeString(const std::string& section, const std::string& name,
                             const std::string& str) {
    set(section, name, str);
}

std::string IniOverlay::readString(const std::string& section, const std::string& name,
                                   const std::string& defaultStr, bool failIfNotFound) const {
    const auto it = values_.find({section, name});
    if (it != values_.end()) return it->second;
    return base_.read_string(section, name, defaultStr, failIfNotFound);
}

}  // namespace lodestone::config
