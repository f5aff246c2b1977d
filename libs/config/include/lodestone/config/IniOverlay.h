#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <map>
#include <string>
#include <utility>

namespace lodestone::config {

/** An INI seen through a few keys set on top of it: reads find the overlay's value first, then
 * the base's; sections and keys are the union of both. How a caller configures a component
 * through its own INI keys (a simulated robot's wheel geometry into [wheel_odometry]) without
 * reaching into the component. The base must outlive the overlay; error messages name it as
 * `sourceName` (config::sourceName gives it). */
class IniOverlay : public mrpt::config::CConfigFileBase {
  public:
    IniOverlay(const mrpt::config::CConfigFileBase& base, std::string sourceName);

    /** Sets `key` of `section` to `value`, whatever the base says. */
    void set(const std::string& section, const std::string& key, const std::string& value);
    /** A number as text that reads back to the same double. */
    void set(const std::string& section, const std::string& key, double value);

    const std::string& name() const { return name_; }

    void getAllSections(std::vector<std::string>& sections) const override;
    void getAllKeys(const std::string& section, std::vector<std::string>& keys) const override;
    /** The base is not ours to empty: throws std::logic_error. */
    void clear() override;

  protected:
    void writeString(const std::string& section, const std::string& name,
                     const std::string& str) override;
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& defaultStr, bool failIfNotFound) const override;

  private:
    const mrpt::config::CConfigFileBase& base_;
    std::string name_;
    std::map<std::pair<std::string, std::string>, std::string> values_;  // (section, key)
};

}  // namespace lodestone::config
