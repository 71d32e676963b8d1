#include "app/command_record.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include <cpl_json.h>
#include <gdal_priv.h>
#include <netcdf.h>
#include <ogrsf_frmts.h>

#include "core/text.h"
#include "gis/gdal_env.h"

namespace isoquad {

namespace {

// The value of the metadata row `key` of an isoquad GeoPackage, or nullopt.
std::optional<std::string> geopackage_metadata(const std::string& path, const char* key) {
  ensure_gdal_registered();
  const GdalErrorCapture quiet;  // a file that is not one of ours: no record
  GdalDataset ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  OGRLayer* layer = ds ? ds->GetLayerByName("metadata") : nullptr;
  if (!layer || layer->GetLayerDefn()->GetFieldIndex("key") < 0 ||
      layer->GetLayerDefn()->GetFieldIndex("value") < 0)
    return std::nullopt;
  layer->ResetReading();
  for (auto& feature : *layer)
    if (std::string(feature->GetFieldAsString("key")) == key)
      return std::string(feature->GetFieldAsString("value"));
  return std::nullopt;
}

// The global attribute `name` of a netCDF file as text, or nullopt.
std::optional<std::string> netcdf_global_text(const std::string& path, const char* name) {
  const std::lock_guard<std::recursive_mutex> lock(netcdf_mutex());
  int id = -1;
  if (nc_open(path.c_str(), NC_NOWRITE, &id) != NC_NOERR) return std::nullopt;
  std::size_t length = 0;
  nc_type type = NC_NAT;
  std::optional<std::string> text;
  if (nc_inq_att(id, NC_GLOBAL, name, &type, &length) == NC_NOERR && type == NC_CHAR) {
    std::string value(length, '\0');
    if (nc_get_att_text(id, NC_GLOBAL, name, value.data()) == NC_NOERR) text = value;
  }
  nc_close(id);
  return text;
}

// The report's "command_line", or nullopt.
std::optional<std::string> report_command_line(const std::string& path) {
  CPLJSONDocument doc;
  const GdalErrorCapture quiet;  // cut short, or not JSON: no record
  if (!doc.Load(path)) return std::nullopt;
  const CPLJSONObject line = doc.GetRoot().GetObj("command_line");
  if (!line.IsValid() || line.GetType() != CPLJSONObject::Type::String) return std::nullopt;
  return line.ToString();
}

bool is_option(const std::string& word) {
  return word.size() > 1 && word[0] == '-' && !std::isdigit(static_cast<unsigned char>(word[1])) &&
         word[1] != '.';
}

// A value as compared: a number by its value (5000, 5e3 and 5000.0 alike).
std::string compared(const std::string& word) {
  char* end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  if (!word.empty() && end == word.c_str() + word.size() && std::isfinite(v))
    return printf_string("%.17g", v);
  return word;
}

// An option with its values, or a positional argument (option empty).
struct Group {
  std::string option;              // by its first name (-o and --output alike)
  std::vector<std::string> words;  // as given: the option and its values, or the argument
  std::string key;                 // as compared
};

// The arguments (after the program's name) as groups: --opt=value and -ovalue as the
// option with its value, every argument after "--" positional.
std::vector<Group> groups_of(const std::vector<std::string>& args,
                             const std::map<std::string, OptionShape>& options) {
  std::vector<Group> groups;
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t open = kNone;  // the option still taking values
  int room = 0;              // how many more (negative: any number)
  bool positional_only = false;
  auto value = [&](const std::string& word) {
    groups[open].words.push_back(word);
    groups[open].key += "\n" + compared(word);
    if (room > 0) --room;
  };
  for (const std::string& arg : args) {
    if (!positional_only && arg == "--") {
      positional_only = true;
      open = kNone;
      continue;
    }
    if (positional_only || !is_option(arg)) {
      if (open != kNone && room != 0 && !positional_only) {
        value(arg);
        continue;
      }
      open = kNone;
      groups.push_back(Group{"", {arg}, compared(arg)});
      continue;
    }
    std::string name = arg, attached;
    bool has_attached = false;
    const std::size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos && eq > 2) {
      name = arg.substr(0, eq), attached = arg.substr(eq + 1), has_attached = true;
    } else if (arg.rfind("--", 0) != 0 && arg.size() > 2) {  // -ovalue
      const auto known = options.find(arg.substr(0, 2));
      if (known != options.end() && known->second.values != 0)
        name = arg.substr(0, 2), attached = arg.substr(2), has_attached = true;
    }
    const auto known = options.find(name);
    const std::string canonical = known == options.end() ? name : known->second.name;
    groups.push_back(Group{canonical, {name}, canonical});
    open = groups.size() - 1;
    room = known == options.end() ? -1 : known->second.values;
    if (has_attached) {
      // A value given with '=' belongs to its option, a flag's too (--repair=false).
      groups[open].words.back() = arg;
      groups[open].key += "\n" + compared(attached);
      room = room > 0 ? room - 1 : room < 0 ? -1 : 0;
    }
  }
  return groups;
}

std::string shown(const Group& g) {
  std::string text;
  for (const std::string& w : g.words) text += (text.empty() ? "" : " ") + shell_quoted(w);
  return text;
}

// A recorded command split from its region's selection (" [--each: ...]").
std::pair<std::string, std::string> without_region(const std::string& line) {
  for (const char* mark : {" [--each: ", " [--each-clip: "}) {
    const std::size_t at = line.rfind(mark);
    if (at != std::string::npos && !line.empty() && line.back() == ']')
      return {line.substr(0, at), line.substr(at + 1)};
  }
  return {line, ""};
}

}  // namespace

std::string shell_quoted(const std::string& arg) {
  const bool plain = !arg.empty() && arg.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyz"
                                         "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789-_./,:=+@%") == std::string::npos;
  if (plain) return arg;
  std::string q = "'";
  for (char c : arg) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<std::string> shell_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '\'')
        quoted = false;
      else
        word += c;
    } else if (c == '\'') {
      quoted = any = true;
    } else if (c == '\\' && i + 1 < line.size()) {
      word += line[++i];
      any = true;
    } else if (c == ' ') {
      if (any) words.push_back(word);
      word.clear();
      any = false;
    } else {
      word += c;
      any = true;
    }
  }
  if (any) words.push_back(word);
  return words;
}

std::optional<RecordedCommand> recorded_command(const std::vector<MeshOutput>& meshes,
                                                const std::string& report_path,
                                                std::vector<std::string>* unreadable) {
  std::error_code ec;
  auto note = [&](const std::string& path) {
    if (unreadable && std::filesystem::exists(path, ec)) unreadable->push_back(path);
  };
  std::optional<RecordedCommand> found;
  if (!report_path.empty() && report_path != "-") {
    if (std::optional<std::string> line = report_command_line(report_path))
      found = RecordedCommand{report_path, *line};
    else
      note(report_path);
  }
  for (const MeshFormat format : {MeshFormat::gpkg, MeshFormat::nc})
    for (const MeshOutput& o : meshes) {
      if (mesh_output_format(o) != format || (found && !unreadable)) continue;
      const std::optional<std::string> line = format == MeshFormat::gpkg
                                                  ? geopackage_metadata(o.path, "command_line")
                                                  : netcdf_global_text(o.path, "history");
      if (!line)
        note(o.path);
      else if (!found)
        found = RecordedCommand{o.path, *line};
    }
  return found;
}

std::string command_difference(const std::string& recorded, const std::string& current,
                               const std::map<std::string, OptionShape>& options,
                               const std::vector<std::string>& ignored) {
  const auto [old_line, old_region] = without_region(recorded);
  const auto [new_line, new_region] = without_region(current);
  auto groups = [&](const std::string& line) {
    std::vector<std::string> args = shell_words(line);
    if (!args.empty()) args.erase(args.begin());  // the program
    std::vector<Group> all = groups_of(args, options), kept;
    for (Group& g : all)
      if (std::find(ignored.begin(), ignored.end(), g.option) == ignored.end())
        kept.push_back(std::move(g));
    return kept;
  };
  std::vector<Group> was = groups(old_line), is = groups(new_line);
  // What both have, taken out one for one.
  for (auto it = was.begin(); it != was.end();) {
    const auto same =
        std::find_if(is.begin(), is.end(), [&](const Group& g) { return g.key == it->key; });
    if (same == is.end()) {
      ++it;
      continue;
    }
    is.erase(same);
    it = was.erase(it);
  }
  std::vector<std::string> clauses;
  // An option (or a positional argument) on both sides with other values: said as one.
  for (auto it = was.begin(); it != was.end();) {
    const auto other =
        std::find_if(is.begin(), is.end(), [&](const Group& g) { return g.option == it->option; });
    if (other == is.end()) {
      ++it;
      continue;
    }
    clauses.push_back("it had " + shown(*it) + " where this command has " + shown(*other));
    is.erase(other);
    it = was.erase(it);
  }
  for (const Group& g : was)
    clauses.push_back("it had " + shown(g) + ", which this command leaves out");
  for (const Group& g : is) clauses.push_back("this command adds " + shown(g));
  if (old_region != new_region)
    clauses.push_back("its region was " + (old_region.empty() ? "none" : old_region) +
                      ", this command's " + (new_region.empty() ? "none" : new_region));
  std::string text;
  for (std::size_t k = 0; k < clauses.size() && k < 3; ++k) text += (k ? "; " : "") + clauses[k];
  if (clauses.size() > 3) text += "; and " + std::to_string(clauses.size() - 3) + " more";
  return text;
}

}  // namespace isoquad
