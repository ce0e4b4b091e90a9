#include "cli_text.h"

#include <algorithm>
#include <cstdio>

namespace brume::app {

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

static std::string choiceAt(std::string_view choices, int index) {
    for (int i = 0; i < index; ++i) {
        const size_t bar = choices.find('|');
        if (bar == std::string_view::npos) return std::string(choices);
        choices.remove_prefix(bar + 1);
    }
    return std::string(choices.substr(0, choices.find('|')));
}

static const char* kindName(SettingKind k) {
    switch (k) {
        case SettingKind::Number: return "number";
        case SettingKind::Integer: return "integer";
        case SettingKind::Vec3: return "vec3";
        case SettingKind::Bool: return "bool";
        case SettingKind::Choice: return "choice";
        case SettingKind::String: return "string";
    }
    return "?";
}

std::string formatDefault(const Setting& s) {
    switch (s.kind) {
        case SettingKind::Vec3:
            return formatNumber(s.def[0]) + ", " + formatNumber(s.def[1]) + ", " + formatNumber(s.def[2]);
        case SettingKind::Bool: return s.b() ? "true" : "false";
        case SettingKind::Choice: return choiceAt(s.choices, s.i());
        case SettingKind::String: return "\"\"";
        default: return formatNumber(s.def[0]);
    }
}

std::string formatRange(const Setting& s) {
    if (s.kind == SettingKind::Choice) return std::string(s.choices);
    if (s.kind == SettingKind::Bool) return "true|false";
    if (s.kind == SettingKind::String) return "any text";
    std::string r = formatNumber(s.min) + ".." + formatNumber(s.max);
    if (!s.unit.empty()) r += " " + std::string(s.unit);
    return r;
}

std::string optionHelp(const Setting& s, std::string_view defaultText) {
    std::string def = defaultText.empty() ? formatDefault(s) : std::string(defaultText);
    if (defaultText.empty() && !s.unit.empty() && s.kind != SettingKind::Choice) def += " " + std::string(s.unit);
    const char* rangeLabel = s.kind == SettingKind::Choice ? " One of: " : " Range: ";
    return std::string(s.help) + rangeLabel + formatRange(s) + ". Default: " + def + ".";
}

std::string settingsPlainTable() {
    size_t pathWidth = 0;
    for (const Setting* s : settings::kAll) pathWidth = std::max(pathWidth, s->path.size());
    char line[512];
    std::snprintf(line, sizeof line, "%-*s  %-8s  %-14s  %-22s  %s\n", static_cast<int>(pathWidth), "setting",
                  "kind", "unit", "default", "range");
    std::string out = line;
    for (const Setting* s : settings::kAll) {
        std::snprintf(line, sizeof line, "%-*s  %-8s  %-14s  %-22s  %s\n", static_cast<int>(pathWidth),
                      std::string(s->path).c_str(), kindName(s->kind),
                      s->unit.empty() ? "-" : std::string(s->unit).c_str(), formatDefault(*s).c_str(),
                      formatRange(*s).c_str());
        out += line;
        out += "    " + std::string(s->help) + "\n";
    }
    return out;
}

}  // namespace brume::app
