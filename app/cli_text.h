// Text built from core/settings.h metadata: option help with unit, default and range, and the
// plain-text settings table of `brume settings`.
#pragma once

#include <string>
#include <string_view>

#include "core/settings.h"

namespace brume::app {

std::string formatNumber(double v);
// Default as a user writes it: "0, 1.5, 6", "true", "high".
std::string formatDefault(const Setting& s);
// Allowed values: "1..16384 px", "low|medium|high|ultra", "any text".
std::string formatRange(const Setting& s);
// "HELP Range: RANGE. Default: DEFAULT." where defaultText replaces the setting's own default
// when non-empty (options that default to a scene value).
std::string optionHelp(const Setting& s, std::string_view defaultText = {});
// Every scene setting, one entry per setting: path, kind, unit, default, range, then the help.
std::string settingsPlainTable();

}  // namespace brume::app
