#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace lodestone::config {

/** A configuration mistake: the message names the file, the section and the key. */
class ConfigError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/** Strict reading of one INI section. Every getter records its key; `finish()` then rejects
 * any key in the file that no getter asked for, so a typo ("sped = 0.3") is an error instead
 * of a silently ignored line. Values are parsed strictly ("0.3m" is an error, not 0.3); text
 * after ';' or '#' on a value line is a comment.
 * Parameter structs (`Params : mrpt::config::CLoadableOptions`) read themselves through it. */
class IniSection {
  public:
    IniSection(const mrpt::config::CConfigFileBase& cfg, std::string section,
               std::string sourceName);

    double getDouble(const std::string& key, double defaultValue);
    double requireDouble(const std::string& key);
    int getInt(const std::string& key, int defaultValue);
    bool getBool(const std::string& key, bool defaultValue);
    std::string getString(const std::string& key, const std::string& defaultValue);
    std::string requireString(const std::string& key);
    /** Whitespace-separated numbers; `expectedCount` 0 means any count. */
    std::vector<double> getDoubles(const std::string& key, const std::vector<double>& defaultValue,
                                   std::size_t expectedCount = 0);

    bool has(const std::string& key) const;
    /** Keys starting with `prefix` present in the file, in file order (e.g. "wall_"), marked
     * as known. */
    std::vector<std::string> keysWithPrefix(const std::string& prefix);

    /** Throws ConfigError naming the first key present in the file but never read. */
    void finish() const;

    /** "file [section] key 'k'": where a value came from, for messages. */
    std::string where(const std::string& key) const;
    [[noreturn]] void fail(const std::string& key, const std::string& why) const;
    const std::string& section() const { return section_; }

  private:
    std::string raw(const std::string& key) const;

    const mrpt::config::CConfigFileBase& cfg_;
    std::string section_, source_;
    std::set<std::string> known_;
};

/** Throws ConfigError if `cfg` has a section not in `allowed` (a misspelt section name). */
void checkSections(const mrpt::config::CConfigFileBase& cfg, const std::set<std::string>& allowed,
                   const std::string& sourceName);

/** Strict number parsing shared by the getters: the whole text must be the number. */
bool parseDouble(const std::string& text, double& out);

}  // namespace lodestone::config

namespace lodestone::config {
/** The file behind a configuration source, for messages ("config" if it has none). */
std::string sourceName(const mrpt::config::CConfigFileBase& cfg);
}  // namespace lodestone::config
