#include "report/search_page.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/xml_text.hpp"

namespace orch::report {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kSize = 420;  // plot square, px
constexpr double kMargin = 56;

// The page's text and attribute values, escaped as in the orchestrator's XML files.
std::string escape(const std::string& s) { return xml_escape(s); }

std::string number(const json& v) {
  if (!v.is_number()) return "–";
  return fmt::format("{:.4g}", v.get<double>());
}

// Red (most critical, smallest) to blue (largest).
std::string colour(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const int r = static_cast<int>(220 - 170 * t), g = static_cast<int>(60 + 60 * t), b = static_cast<int>(50 + 180 * t);
  return fmt::format("rgb({},{},{})", r, g, b);
}

// A parameter's axis label: its key and unit ("lead.speed (km/h)").
std::string axis_label(const json& dim) {
  const std::string unit = dim.value("unit", "");
  return dim.value("key", "") + (unit.empty() ? "" : " (" + unit + ")");
}

// The acquisition value of a proposal, named by its kind (search.json's `acquisition`).
std::string acquisition_text(const json& run) {
  const double a = run.value("acquisition", 0.0);
  if (a == 0) return "";
  const std::string why = run.value("why", "");
  if (why.find("pattern search") != std::string::npos) return fmt::format(" (step {:.3g} of the ranges)", a);
  if (why.find("expected improvement") != std::string::npos) return fmt::format(" ({:.3g})", a);
  return fmt::format(" (cell {:.3g} of the ranges)", a);
}

std::vector<json> all_runs(const json& search) {
  std::vector<json> runs;
  for (const auto& it : search.value("iterations", json::array()))
    for (const auto& p : it.value("points", json::array())) runs.push_back(p);
  return runs;
}

std::string run_tooltip(const json& run) {
  std::string t;
  for (const auto& [k, v] : run.at("values").items()) t += fmt::format("{} = {}\n", k, number(v));
  t += fmt::format("objective {}  verdict {}  ({})", number(run.value("objective", json())), run.value("verdict", ""),
                   run.value("why", ""));
  return escape(t);
}

// One plot: parameter `ix` across, `iy` up (iy < 0: the objective up).
std::string plot(const json& search, const std::vector<json>& runs, std::size_t ix, int iy) {
  std::optional<std::string> best_id;
  if (search.contains("critical") && !search["critical"].empty()) best_id = search["critical"][0].value("run_id", "");
  const json& dims = search.at("dimensions");
  const json& dx = dims[ix];
  double ylo = 0, yhi = 1;
  std::string ylabel;
  std::vector<double> obj;
  for (const auto& r : runs)
    if (r.value("objective", json()).is_number()) obj.push_back(r["objective"].get<double>());
  const double olo = obj.empty() ? 0 : *std::min_element(obj.begin(), obj.end());
  const double ohi = obj.empty() ? 1 : *std::max_element(obj.begin(), obj.end());
  if (iy >= 0) {
    ylo = dims[static_cast<std::size_t>(iy)].value("lower", 0.0);
    yhi = dims[static_cast<std::size_t>(iy)].value("upper", 1.0);
    ylabel = axis_label(dims[static_cast<std::size_t>(iy)]);
  } else {
    ylo = olo;
    yhi = ohi > olo ? ohi : olo + 1;
    ylabel = search["options"].value("objective", "objective");
  }
  const double xlo = dx.value("lower", 0.0), xhi = dx.value("upper", 1.0);
  const auto px = [&](double v) { return kMargin + (v - xlo) / (xhi - xlo) * kSize; };
  const auto py = [&](double v) { return kMargin + kSize - (v - ylo) / (yhi - ylo) * kSize; };
  std::string svg = fmt::format(R"(<svg class="space" width="{}" height="{}" xmlns="http://www.w3.org/2000/svg">)",
                                kSize + 2 * kMargin, kSize + 2 * kMargin);
  svg += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#fafafa" stroke="#888"/>)", kMargin, kMargin, kSize, kSize);
  // The shaded lattice cells are centred on the lattice points: clipped to the plot, the
  // outer ones do not spill over the axes.
  svg += fmt::format(R"(<clipPath id="plot-area-{0}-{1}"><rect x="{2}" y="{2}" width="{3}" height="{3}"/></clipPath>)", ix, iy,
                     kMargin, kSize);
  // The boundary estimate (2 parameters only): failing cells shaded.
  if (search.contains("boundary") && dims.size() == 2 && iy == 1) {
    const json& b = search["boundary"];
    const auto levels = b.value("levels", std::size_t{0});
    const std::string pass = b.value("pass", "");
    const double cell = kSize / static_cast<double>(levels - 1);
    for (std::size_t i = 0; i < levels; ++i)
      for (std::size_t j = 0; j < levels; ++j) {
        if (i * levels + j >= pass.size() || pass[i * levels + j] == '1') continue;
        const double cx = kMargin + static_cast<double>(i) * cell, cy = kMargin + kSize - static_cast<double>(j) * cell;
        svg += fmt::format(
            R"x(<rect class="fail-cell" x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#f4c7c3" clip-path="url(#plot-area-{}-{})"/>)x",
            cx - cell / 2, cy - cell / 2, cell, cell, ix, iy);
      }
  }
  for (const auto& r : runs) {
    const json& values = r.at("values");
    const double x = values.value(dx.value("key", ""), 0.0);
    double y = 0;
    if (iy >= 0) y = values.value(dims[static_cast<std::size_t>(iy)].value("key", ""), 0.0);
    else if (r.value("objective", json()).is_number()) y = r["objective"].get<double>();
    else continue;
    const json o = r.value("objective", json());
    const std::string fill = o.is_number() ? colour(ohi > olo ? (o.get<double>() - olo) / (ohi - olo) : 0.5) : "#999";
    const bool failed = r.value("pass", json()).is_boolean() ? !r["pass"].get<bool>() : r.value("verdict", "") != "success";
    if (best_id && r.value("run_id", "") == *best_id)  // the most critical run: a wide gold ring under its dot
      svg += fmt::format(R"(<circle class="best" cx="{:.1f}" cy="{:.1f}" r="10" fill="none" stroke="#e0a800" stroke-width="3"/>)",
                         px(x), py(y));
    svg += fmt::format(R"(<a href="{}/report.html"><circle class="run" cx="{:.1f}" cy="{:.1f}" r="5" fill="{}" stroke="{}" stroke-width="{}"><title>{}</title></circle></a>)",
                       escape(r.value("run_dir", "")), px(x), py(y), fill, failed ? "#000" : "#fff", failed ? 2 : 1,
                       run_tooltip(r));
  }
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">{}</text>)", kMargin + kSize / 2, kSize + kMargin + 40,
                     escape(axis_label(dx)));
  svg += fmt::format(R"x(<text x="14" y="{}" transform="rotate(-90 14 {})" text-anchor="middle">{}</text>)x",
                     kMargin + kSize / 2, kMargin + kSize / 2, escape(ylabel));
  for (int k = 0; k <= 4; ++k) {
    const double fx = xlo + (xhi - xlo) * k / 4, fy = ylo + (yhi - ylo) * k / 4;
    svg += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="11" text-anchor="middle">{:.3g}</text>)", px(fx),
                       kSize + kMargin + 16, fx);
    svg += fmt::format(R"(<text x="{}" y="{:.1f}" font-size="11" text-anchor="end">{:.3g}</text>)", kMargin - 8, py(fy) + 4, fy);
  }
  return svg + "</svg>";
}

// What the dots' colours mean: the objective's scale from red (smallest, most critical) to
// blue, with its values, so that a colour can be read without hovering over every dot.
std::string colour_legend(const std::string& objective, const std::vector<json>& runs) {
  std::vector<double> obj;
  for (const auto& r : runs)
    if (r.value("objective", json()).is_number()) obj.push_back(r["objective"].get<double>());
  if (obj.empty()) return ", grey (no objective)";
  const double lo = *std::min_element(obj.begin(), obj.end()), hi = *std::max_element(obj.begin(), obj.end());
  std::string bar = R"(<svg width="160" height="12" style="vertical-align:middle;margin:0 4px">)";
  for (int k = 0; k < 16; ++k)
    bar += fmt::format(R"(<rect x="{}" y="0" width="10" height="12" fill="{}"/>)", k * 10, colour(k / 15.0));
  bar += "</svg>";
  return fmt::format(" coloured by {}: {} {} {} (red = smallest, the most critical); grey: no value", escape(objective),
                     number(lo), bar, number(hi));
}

// Runs are numbered in the order the search proposed them (run ids all begin with the logical
// scenario's uuid: shortened, they looked alike); the full id is the link's tooltip.
std::string runs_table(const std::vector<json>& runs, const json& dims, const std::map<std::string, std::size_t>& number_of) {
  std::string h = "<table><tr><th>run</th>";
  for (const auto& d : dims) h += "<th>" + escape(d.value("key", "")) + "</th>";
  h += "<th>objective</th><th>verdict</th><th>why</th></tr>";
  for (const auto& r : runs) {
    const auto n = number_of.find(r.value("run_id", ""));
    h += fmt::format(R"(<tr><td><a href="{}/report.html" title="{}">{}</a></td>)", escape(r.value("run_dir", "")),
                     escape(r.value("run_id", "")), n == number_of.end() ? "run" : fmt::format("run {}", n->second));
    for (const auto& d : dims) h += "<td>" + number(r.at("values").value(d.value("key", ""), json())) + "</td>";
    h += fmt::format("<td>{}</td><td>{}</td><td>{}{}</td></tr>", number(r.value("objective", json())),
                     escape(r.value("verdict", "")), escape(r.value("why", "")), acquisition_text(r));
  }
  return h + "</table>";
}

}  // namespace

std::string search_page_html(const json& search) {
  const json& o = search.at("options");
  const json& dims = search.at("dimensions");
  const std::vector<json> runs = all_runs(search);
  std::map<std::string, std::size_t> number_of;
  for (std::size_t i = 0; i < runs.size(); ++i) number_of[runs[i].value("run_id", "")] = i + 1;
  const std::string boundary = o.value("boundary", "");
  std::string h = R"(<!DOCTYPE html><html><head><meta charset="utf-8"><title>Search</title><style>
body{font-family:sans-serif;margin:1.5em;color:#222}table{border-collapse:collapse;margin:.5em 0}
td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}svg.space{margin:4px;border:0}.plots{display:flex;flex-wrap:wrap}
</style></head><body>)";
  h += fmt::format("<h1>Search: {}</h1>", boundary.empty() ? "minimum of " + escape(o.value("objective", ""))
                                                            : "pass/fail boundary of " + escape(boundary));
  h += fmt::format("<p>{} — method {}, {} runs of a budget of {}, {} at a time, seed {}{}.</p>",
                   escape(o.value("input", "")), escape(o.value("method", "")), search.value("runs", 0),
                   o.value("budget", 0), o.value("jobs", 0), o.value("seed", 0),
                   search.value("finished", false) ? "" : " (not finished: continue with --resume)");
  if (!search.at("fixed").empty()) {
    std::string fixed;
    for (const auto& [k, v] : search["fixed"].items()) fixed += (fixed.empty() ? "" : ", ") + k + " = " + (v.is_number() ? number(v) : v.dump());
    h += "<p>Fixed parameters: " + escape(fixed) + "</p>";
  }
  if (search.contains("boundary"))
    h += fmt::format("<p id=\"boundary\">Boundary estimate ({}): failure over {:.1f} % of the space (shaded); "
                     "the boundary lies in cells whose corners disagree, {:.1f} % of the space{}.</p>",
                     o.value("method", "") == "bo" ? "sparse grid: corners of the smallest run cells interpolated"
                                                   : "a Gaussian process fitted to pass +1 / fail -1",
                     100 * (1 - search["boundary"].value("pass_fraction", 0.0)),
                     100 * search["boundary"].value("uncertain_fraction", 0.0),
                     o.value("method", "") == "bo" && search.value("finished", false) && search.value("runs", 0) < o.value("budget", 0)
                         ? fmt::format(" (resolved: each down to {:g} of the ranges)", o.value("resolution", 0.0))
                         : "");
  h += "<p>Dots: runs" + colour_legend(o.value("objective", ""), runs) +
       (search.contains("critical") && !search["critical"].empty() ? "; a gold ring = the most critical run" : "") +
       "; a black ring = failed" + (boundary.empty() ? " (verdict not success)" : " (" + escape(boundary) + ")") +
       ". Click a dot for its run report.</p><div class=\"plots\">";
  if (dims.size() == 1) h += plot(search, runs, 0, -1);
  for (std::size_t i = 0; i < dims.size(); ++i)
    for (std::size_t j = i + 1; j < dims.size() && j < i + 2 + (dims.size() > 3 ? 0 : 1); ++j)
      h += plot(search, runs, i, static_cast<int>(j));
  h += "</div>";
  if (search.contains("critical")) {
    h += "<h2>Most critical runs</h2>";
    h += runs_table(search["critical"].get<std::vector<json>>(), dims, number_of);
  }
  h += "<h2>Iterations</h2><table><tr><th>#</th><th>runs</th><th>why</th><th>best so far</th><th>uncertain</th></tr>";
  for (const auto& it : search.value("iterations", json::array())) {
    const json best = it.value("best_so_far", json());
    std::string why;  // every kind of point the iteration proposed (a poll may be filled up with others)
    for (const auto& p : it.value("points", json::array())) {
      const std::string w = p.value("why", "");
      if (why.find(w) == std::string::npos) why += (why.empty() ? "" : ", ") + w;
    }
    h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>", it.value("iteration", 0),
                     it.value("runs_so_far", 0), escape(why),
                     best.is_object() ? fmt::format(R"(<a href="{}/report.html">{}</a>)", escape(best.value("run_dir", "")),
                                                    number(best.value("objective", json())))
                                      : "–",
                     it.contains("uncertain_fraction") ? fmt::format("{:.1f} %", 100 * it["uncertain_fraction"].get<double>())
                                                       : "–");
  }
  h += "</table><h2>Every run</h2>" + runs_table(runs, dims, number_of);
  h += R"(<p><a href="report.html">The batch report of these runs</a></p></body></html>)";
  return h;
}

fs::path write_search_report(const fs::path& dir) {
  const fs::path file = dir / "search.json";
  if (!fs::exists(file)) throw OrchError(fmt::format("{}: no search.json", dir.string()));
  const fs::path out = dir / "search.html";
  write_file_atomically(out, search_page_html(json::parse(read_file(file))));
  return out;
}

}  // namespace orch::report
