#include <lodestone/config/IniSection.h>

#include <cmath>
#include <sstream>

namespace lodestone::config {

namespace {
std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}
}  // namespace

bool parseDouble(const std::string& text, double& out) {
    const std::string t = trim(text);
    if (t.empty()) return false;
    std::size_t used = 0;
    try {
        out = std::stod(t, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == t.size() && std::isfinite(out);
}

IniSection::IniSection(const mrpt::config::CConfigFileBase& cfg, std::string section,
                       std::string sourceName)
    : cfg_(cfg), section_(std::move(section)), source_(std::move(sourceName)) {}

std::string IniSection::where(const std::string& key) const {
    return source_ + " [" + section_ + "] key '" + key + "'";
}

void IniSection::fail(const std::string& key, const std::string& why) const {
    throw ConfigError(where(key) + ": " + why);
}

bool IniSection::has(const std::string& key) const { return cfg_.keyExists(section_, key); }

std::string IniSection::raw(const std::string& key) const {
    // MRPT keeps text after the value; Lodestone's INIs comment values with ';' or '#'.
    std::string value = cfg_.read_string(section_, key, "", false);
    const auto comment = value.find_first_of(";#");
    if (comment != std::string::npos) value.resize(comment);
    return trim(value);
}

double IniSection::getDouble(const std::string& key, double defaultValue) {
    known_.insert(key);
    if (!has(key)) return defaultValue;
    double v = 0;
    if (!parseDouble(raw(key), v)) fail(key, "expected a number, got '" + raw(key) + "'");
    return v;
}

double IniSection::requireDouble(const std::string& key) {
    if (!has(key)) fail(key, "missing (required)");
    return getDouble(key, 0.0);
}

int IniSection::getInt(const std::string& key, int defaultValue) {
    const double v = getDouble(key, defaultValue);
    if (v != std::floor(v) || std::abs(v) > 2e9) fail(key, "expected an integer");
    return static_cast<int>(v);
}

bool IniSection::getBool(const std::string& key, bool defaultValue) {
    known_.insert(key);
    if (!has(key)) return defaultValue;
    const std::string v = raw(key);
    if (v == "true" || v == "1" || v == "yes") return true;
    if (v == "false" || v == "0" || v == "no") return false;
    fail(key, "expected true/false, got '" + v + "'");
}

std::string IniSection::getString(const std::string& key, const std::string& defaultValue) {
    known_.insert(key);
    return has(key) ? raw(key) : defaultValue;
}

std::string IniSection::requireString(const std::string& key) {
    if (!has(key)) fail(key, "missing (required)");
    return getString(key, "");
}

std::vector<double> IniSection::getDoubles(const std::string& key,
                                           const std::vector<double>& defaultValue,
                                           std::size_t expectedCount) {
    known_.insert(key);
    if (!has(key)) return defaultValue;
    std::istringstream in(raw(key));
    std::vector<double> values;
    for (std::string word; in >> word;) {
        double v = 0;
        if (!parseDouble(word, v)) fail(key, "expected numbers, got '" + word + "'");
        values.push_back(v);
    }
    if (expectedCount && values.size() != expectedCount) {
        fail(key, "expected " + std::to_string(expectedCount) + " numbers, got " +
                      std::to_string(values.size()));
    }
    return values;
}

std::vector<std::string> IniSection::keysWithPrefix(const std::string& prefix) {
    std::vector<std::string> all, out;
    cfg_.getAllKeys(section_, all);
    for (const auto& k : all) {
        if (k.rfind(prefix, 0) == 0) {
            out.push_back(k);
            known_.insert(k);
        }
    }
    return out;
}

void IniSection::finish() const {
    std::vector<std::string> all;
    cfg_.getAllKeys(section_, all);
    for (const auto& k : all) {
        if (!known_.count(k)) {
            std::string expected;
            for (const auto& known : known_) expected += (expected.empty() ? "" : ", ") + known;
            fail(k, "unknown key (this section takes: " + expected + ")");
        }
    }
}

void checkSections(const mrpt::config::CConfigFileBase& cfg, const std::set<std::string>& allowed,
                   const std::string& sourceName) {
    std::vector<std::string> sections;
    cfg.getAllSections(sections);
    for (const auto& s : sections) {
        if (s.empty() || allowed.count(s)) continue;
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw ConfigError(sourceName + ": unknown section [" + s + "] (known: " + list + ")");
    }
}

}  // namespace lodestone::config

#include <lodestone/config/IniOverlay.h>
#include <mrpt/config/CConfigFile.h>

namespace lodestone::config {
std::string sourceName(const mrpt::config::CConfigFileBase& cfg) {
    if (const auto* file = dynamic_cast<const mrpt::config::CConfigFile*>(&cfg)) {
        return file->getAssociatedFile();
    }
    if (const auto* overlay = dynamic_cast<const IniOverlay*>(&cfg)) return overlay->name();
    return "config";
}
}  // namespace lodestone::config
