// What to tell a user whose attribute filter (--where, --clip-where) selects no feature.
#pragma once

#include <string>
#include <vector>

class OGRLayer;

namespace isoquad {

// The values of `candidates` nearest `typed`, ignoring case: those within an edit
// distance of a third of its length (at least 1), then those that hold it whole (when it
// has 3 characters or more), nearest first, ties by value; at most `most`.
std::vector<std::string> nearest_values(const std::string& typed,
                                        const std::vector<std::string>& candidates,
                                        std::size_t most = 3);

// Why `where` (OGR SQL, set on `layer` as its attribute filter) selects no feature, for
// each quoted value in it that no feature selected by the layer's spatial filter holds
// in a text attribute that `where` names: that the features holding it lie outside the
// spatial filter (`area`: what set it, e.g. "the bbox"), or the nearest values the
// attribute holds (nearest_values). Empty when there is nothing to say. Reads the layer
// without its attribute filter (and once without its spatial filter) and sets both
// again before it returns.
std::string where_hint(OGRLayer& layer, const std::string& where, const std::string& area);

// What to add to OGR's `message` when `where` is no valid filter on `layer`: its
// attributes with their types, " (attributes: id (String), name (String))", and, where OGR
// took a word for an attribute it lacks, the nearest attributes' names, and a reminder
// that text values are quoted when the word follows a comparison ("name = Belgium").
std::string filter_help(OGRLayer& layer, const std::string& where, const std::string& message);

}  // namespace isoquad
