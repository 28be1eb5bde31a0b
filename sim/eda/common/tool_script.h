// The tools' scripts (Yosys, ABC, OpenSTA) are files beside their drivers, which read and fill
// them in here, as the layout flow's are: each file says in its header what it does and how to
// run it by hand.
#pragma once

#include <map>
#include <string>

namespace shadesim {

// The commands of the script at `path` (relative to this build's checkout): the file less its
// comment lines ('#' first). The tools get the commands only, so a reworded comment changes
// neither what they run nor the cache keys that hash the commands. A missing or unreadable file
// is an error naming it.
std::string tool_script(const std::string& path);

// `text` less its comment lines.
std::string script_commands(const std::string& text);

// `text` with every occurrence of each key of `values` (an @NAME@ field) replaced by its value.
std::string fill_placeholders(std::string text, const std::map<std::string, std::string>& values);

}  // namespace shadesim
