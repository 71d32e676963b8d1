// Human-readable and JSON forms of the front end's summary.
#pragma once

#include <string>

#include "app/front_end.h"
#include "core/json_writer.h"

namespace isoquad {

std::string format_domain_summary(const DomainSummary& s);
std::string domain_summary_json(const DomainSummary& s);
// Adds the summary's members to the object being written.
void add_domain_summary(JsonWriter& json, const DomainSummary& s);
// Adds what every report opens with: isoquad's version, the command line and the
// libraries' versions (app/versions.h).
void add_report_header(JsonWriter& json, const std::string& command_line);

}  // namespace isoquad
