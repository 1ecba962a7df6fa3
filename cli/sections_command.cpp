#include "cli/sections_command.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "elements/section_shapes.hpp"

namespace beamfea::cli {

std::unique_ptr<SectionsCommand> add_sections_command(CLI::App& app) {
  auto cmd = std::make_unique<SectionsCommand>();
  cmd->app = app.add_subcommand("sections", "List the section shapes, or compute one shape's properties");
  cmd->app->add_option("shape", cmd->shape, "A shape (omit to list them all)");
  cmd->app->add_option("dimensions", cmd->dimensions, "The shape's dimensions as key=value (e.g. h=0.3 b=0.15)");
  cmd->app->add_flag("--json", cmd->json, "Print the properties (or the list) as JSON");
  return cmd;
}

namespace {

std::string joined(const std::vector<std::string_view>& names, const char* suffix = "") {
  std::string out;
  for (const auto& n : names) out.append(out.empty() ? "" : ", ").append(n).append(suffix);
  return out;
}

int list_shapes(bool json) {
  if (json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const auto& s : section_shapes()) {
      nlohmann::ordered_json o;
      o["shape"] = s.name;
      o["dimensions"] = s.dimensions;
      o["optional"] = s.optional;
      o["description"] = s.description;
      o["formulas"] = s.formulas;
      out.push_back(std::move(o));
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << "Section shapes (\"shape\" of a section; b along local y, h along local z; any consistent units):\n";
  for (const auto& s : section_shapes()) {
    std::cout << "\n" << s.name << ": " << joined(s.dimensions);
    if (!s.optional.empty()) std::cout << (s.dimensions.empty() ? "" : ", ") << joined(s.optional, " (optional)");
    std::cout << "\n  " << s.description << "\n  " << s.formulas << "\n";
  }
  std::cout << "\nbeamfea sections <shape> key=value ...   computes one section's properties\n";
  return 0;
}

}  // namespace

int run_sections_command(const SectionsCommand& cmd) {
  if (cmd.shape.empty()) return list_shapes(cmd.json);
  try {
    std::vector<std::pair<std::string, double>> dims;
    for (const auto& kv : cmd.dimensions) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("'" + kv + "': expected key=value");
      const std::string key = kv.substr(0, eq), text = kv.substr(eq + 1);
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0') throw std::invalid_argument(key + ": '" + text + "' is not a number");
      dims.emplace_back(key, v);
    }
    const SectionProperties p = section_properties(cmd.shape, dims);
    const PrincipalMoments pm = principal_moments(p.Iy, p.Iz, p.Iyz);
    if (cmd.json) {
      nlohmann::ordered_json o{{"shape", cmd.shape}, {"A", p.A},   {"Iy", p.Iy},     {"Iz", p.Iz},
                               {"J", p.J},           {"ky", p.ky}, {"kz", p.kz},     {"Iyz", p.Iyz},
                               {"I1", pm.I1},        {"I2", pm.I2}, {"principal_angle", pm.angle}};
      std::cout << o.dump(2) << "\n";
    } else {
      std::cout << fmt::format("{}: A = {:.6g}, Iy = {:.6g}, Iz = {:.6g}, J = {:.6g}, ky = {:.6g}, kz = {:.6g}\n", cmd.shape, p.A,
                               p.Iy, p.Iz, p.J, p.ky, p.kz);
      if (p.Iyz != 0.0)
        std::cout << fmt::format("  Iyz = {:.6g} (neglected by the beam element); principal I1 = {:.6g}, I2 = {:.6g}, "
                                 "I1's axis at {:.6g} rad from local y towards z\n",
                                 p.Iyz, pm.I1, pm.I2, pm.angle);
    }
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << "beamfea: error: sections " << cmd.shape << ": " << e.what() << "\n";
    return 2;
  }
}

}  // namespace beamfea::cli
