#pragma once

#include <lodestone/config/IniSection.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <string>

namespace lodestone::test {

/** What `decider.configure` says of an INI text: the configuration error's message, or
 * "no error". */
template <typename Decider>
std::string configErrorOf(Decider& decider, const std::string& text) {
    mrpt::config::CConfigFileMemory ini(text);
    try {
        decider.configure(ini);
    } catch (const config::ConfigError& e) {
        return std::string(e.what());
    }
    return std::string("no error");
}

}  // namespace lodestone::test
