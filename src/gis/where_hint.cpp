#include "gis/where_hint.h"

#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <set>
#include <utility>

#include "core/text.h"

namespace isoquad {

namespace {

// Levenshtein distance, one row at a time.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A string literal of an SQL expression ('...', '' standing for a quote inside) and
// where it starts.
struct Literal {
  std::string value;
  std::size_t at;
};

std::vector<Literal> quoted_values(const std::string& sql) {
  std::vector<Literal> values;
  for (std::size_t i = 0; i < sql.size(); ++i) {
    if (sql[i] != '\'') continue;
    Literal literal{"", i};
    for (++i; i < sql.size(); ++i) {
      if (sql[i] == '\'' && i + 1 < sql.size() && sql[i + 1] == '\'') {
        literal.value += '\'';
        ++i;
      } else if (sql[i] == '\'') {
        break;
      } else {
        literal.value += sql[i];
      }
    }
    values.push_back(literal);
  }
  return values;
}

// Where the SQL expression names `field` outside its string literals: as a word of its
// own (any case), or in double quotes.
std::vector<std::size_t> field_mentions(const std::string& sql, const std::string& field) {
  std::string outside;  // the expression with its literals blanked
  bool in_literal = false;
  for (char c : sql) {
    if (c == '\'') in_literal = !in_literal;
    outside += in_literal || c == '\'' ? ' ' : c;
  }
  const std::string text = lower_case(outside), name = lower_case(field);
  auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  std::vector<std::size_t> mentions;
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    const std::size_t end = at + name.size();
    const bool quoted = at > 0 && text[at - 1] == '"' && end < text.size() && text[end] == '"';
    if (quoted ||
        ((at == 0 || !word_char(text[at - 1])) && (end == text.size() || !word_char(text[end]))))
      mentions.push_back(at);
  }
  return mentions;
}

// Whether the literal starting at `at` follows LIKE or ILIKE.
bool after_like(const std::string& sql, std::size_t at) {
  std::size_t end = at;
  while (end > 0 && std::isspace(static_cast<unsigned char>(sql[end - 1]))) --end;
  return end >= 4 && lower_case(sql.substr(end - 4, 4)) == "like" &&
         (end == 4 || !std::isalnum(static_cast<unsigned char>(sql[end - 5])));
}

std::string quote(const std::string& s) {
  return "'" + s + "'";
}

}  // namespace

std::vector<std::string> nearest_values(const std::string& typed,
                                        const std::vector<std::string>& candidates,
                                        std::size_t most) {
  const std::string t = lower_case(typed);
  const std::size_t limit = std::max<std::size_t>(1, t.size() / 3);
  std::vector<std::pair<std::size_t, std::string>> ranked;  // (rank, value)
  for (const std::string& c : candidates) {
    const std::string l = lower_case(c);
    const std::size_t d = edit_distance(t, l);
    if (d <= limit)
      ranked.emplace_back(d, c);
    else if (t.size() >= 3 && l.find(t) != std::string::npos)
      ranked.emplace_back(limit + 1 + (l.size() - t.size()), c);
  }
  std::sort(ranked.begin(), ranked.end());
  std::vector<std::string> out;
  for (const auto& r : ranked) {
    if (out.size() == most) break;
    if (std::find(out.begin(), out.end(), r.second) == out.end()) out.push_back(r.second);
  }
  return out;
}

std::string where_hint(OGRLayer& layer, const std::string& where, const std::string& area) {
  const std::vector<Literal> typed = quoted_values(where);
  if (typed.empty()) return "";
  // The text fields that `where` names, and which of them each value is compared with:
  // the one named last before it ("name = 'x'", "name IN ('x', 'y')"), else the first
  // after it ("'x' = name").
  OGRFeatureDefn* defn = layer.GetLayerDefn();
  std::vector<int> fields;
  std::vector<std::pair<std::size_t, int>> mentions;  // (where, index into fields)
  for (int i = 0; i < defn->GetFieldCount(); ++i) {
    const OGRFieldDefn* f = defn->GetFieldDefn(i);
    if (f->GetType() != OFTString) continue;
    const std::vector<std::size_t> at = field_mentions(where, f->GetNameRef());
    if (at.empty()) continue;
    for (std::size_t a : at) mentions.emplace_back(a, static_cast<int>(fields.size()));
    fields.push_back(i);
  }
  if (fields.empty()) return "";
  std::sort(mentions.begin(), mentions.end());
  auto field_of = [&](const Literal& literal) {
    int k = -1;
    for (const auto& [at, index] : mentions)
      if (at < literal.at || k < 0)
        k = index;
      else
        break;
    return k;
  };
  // Each field's values, within the spatial filter and, when there is one, beyond.
  const OGRGeometry* filter = layer.GetSpatialFilter();
  std::unique_ptr<OGRGeometry> spatial(filter ? filter->clone() : nullptr);
  auto values_of = [&](bool within) {
    std::vector<std::set<std::string>> values(fields.size());
    layer.SetSpatialFilter(within ? spatial.get() : nullptr);
    layer.ResetReading();
    for (auto& feature : layer)
      for (std::size_t k = 0; k < fields.size(); ++k)
        if (feature->IsFieldSetAndNotNull(fields[k]))
          values[k].insert(feature->GetFieldAsString(fields[k]));
    return values;
  };
  layer.SetAttributeFilter(nullptr);
  const std::vector<std::set<std::string>> inside = values_of(true);
  std::vector<std::set<std::string>> anywhere;
  if (spatial) anywhere = values_of(false);
  layer.SetSpatialFilter(spatial.get());
  layer.SetAttributeFilter(where.c_str());
  layer.ResetReading();

  // OGR SQL compares text ignoring case.
  auto holds = [](const std::set<std::string>& values, const std::string& value) {
    const std::string l = lower_case(value);
    return std::any_of(values.begin(), values.end(),
                       [&](const std::string& v) { return lower_case(v) == l; });
  };
  std::string hint;
  auto add = [&](const std::string& s) { hint += (hint.empty() ? "" : "; ") + s; };
  for (const Literal& literal : typed) {
    if (after_like(where, literal.at)) continue;  // a pattern, not a value
    const int k = field_of(literal);
    const std::string& value = literal.value;
    if (holds(inside[k], value)) continue;  // the filter fails for another reason
    const std::string name = defn->GetFieldDefn(fields[k])->GetNameRef();
    if (spatial && holds(anywhere[k], value)) {
      add("the features with " + name + " " + quote(value) + " lie outside " + area);
      continue;
    }
    const std::vector<std::string> near =
        nearest_values(value, {inside[k].begin(), inside[k].end()});
    std::string listed;
    bool not_utf8 = false;
    for (const std::string& n : near) {
      listed += (listed.empty() ? "" : ", ") + quote(utf8_or_cp1252(n));
      not_utf8 = not_utf8 || !is_utf8(n);
    }
    add("no feature" + std::string(spatial ? " there" : "") + " has " + name + " " + quote(value) +
        (near.empty() ? "" : " (the nearest: " + listed + ")"));
    // OGR compares bytes: a .dbf in Latin-1 without its .cpg never matches UTF-8 text.
    if (not_utf8)
      add("the layer's text is not UTF-8 (shown here as Windows-1252): name its encoding in "
          "a .cpg file beside the .shp (e.g. 'ISO-8859-1' or '1252') or in the environment "
          "variable SHAPE_ENCODING");
  }
  return hint;
}

std::string filter_help(OGRLayer& layer, const std::string& where, const std::string& message) {
  OGRFeatureDefn* defn = layer.GetLayerDefn();
  std::vector<std::string> names;
  std::string attributes;
  for (int i = 0; i < defn->GetFieldCount(); ++i) {
    const OGRFieldDefn* d = defn->GetFieldDefn(i);
    names.push_back(d->GetNameRef());
    attributes +=
        (i ? ", " : "") + names.back() + " (" + OGRFieldDefn::GetFieldTypeName(d->GetType()) + ")";
  }
  std::string help = " (attributes: " + (attributes.empty() ? "none" : attributes);
  // OGR names what it took for an attribute: "X" not recognised as an available field.
  const std::size_t end = message.find("\" not recognised");
  const std::size_t start = end == std::string::npos ? end : message.rfind('"', end - 1);
  if (start != std::string::npos) {
    const std::string unknown = message.substr(start + 1, end - start - 1);
    std::string near;
    for (const std::string& n : nearest_values(unknown, names))
      near += (near.empty() ? "" : " or ") + quote(n);
    if (!near.empty()) help += "; " + quote(unknown) + ": did you mean " + near + "?";
    // After a comparison or in a list, a word meant as a value: OGR SQL's text is quoted.
    const std::size_t at = where.find(unknown);
    std::size_t before = at == std::string::npos || at == 0 ? std::string::npos
                                                            : where.find_last_not_of(" \t", at - 1);
    if (before != std::string::npos &&
        std::string("=<>(,").find(where[before]) != std::string::npos)
      help += "; a text value goes in single quotes: '" + unknown + "'";
  }
  return help + ")";
}

}  // namespace isoquad
