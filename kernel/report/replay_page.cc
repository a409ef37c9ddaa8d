// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay_page.h"

#include <filesystem>
#include <string>
#include <string_view>

#include "replay_page_assets.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using nlohmann::json;

// policy and skeleton are constants: the data only ever goes inside the JSON script element
constexpr std::string_view kHead = R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src data:; base-uri 'none'; form-action 'none'">
)html";

// the elements replay.js fills in (its titles hold ")\"", so the literal has a delimiter)
constexpr std::string_view kBody = R"html(<body>
<h1 id="title">Replay</h1>
<noscript><p>This page draws the replay with JavaScript; please allow it for this file.</p></noscript>
<p id="divergence" hidden></p>
<div id="timeline">
<div id="controls">
<button type="button" id="play" aria-pressed="false" title="play or pause (space)">Play</button>
<button type="button" id="step-back" title="one sample back (left arrow)">&#9664; Step</button>
<button type="button" id="step-forward" title="one sample forward (right arrow)">Step &#9654;</button>
<label>Speed <select id="speed"></select></label>
<button type="button" id="previous-event" title="the previous event">&#8676; Event</button>
<button type="button" id="next-event" title="the next event">Event &#8677;</button>
<span id="time">0.000 s</span>
</div>
<div id="track"><input type="range" id="cursor-range" min="0" max="0" step="any" value="0" aria-label="time"><div id="timeline-marks"></div></div>
</div>
<div id="main">
<div id="scene-box"><canvas id="scene" aria-label="the scene seen from above, north up"></canvas></div>
<div id="side">
<section><h2>Robots</h2><ul id="legend"></ul></section>
<section><h2>HUD</h2><div id="hud"></div></section>
<section><h2>Values</h2><table id="values"><tbody></tbody></table></section>
<section><h2>Events</h2><ol id="events"></ol></section>
</div>
</div>
<h2>Signals</h2>
<div id="plots"></div>
<h2>Log</h2>
<table id="log"><tbody></tbody></table>
)html";

// the data as JSON that cannot end its script element: '<' is written \u003c (so neither
// "</script" nor "<!--" can appear) and U+2028/U+2029 as escapes; both only occur in strings
std::string ScriptSafeJson(const json& data) {
  const std::string dumped = data.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(dumped.size() + dumped.size() / 16);
  for (size_t i = 0; i < dumped.size(); ++i) {
    const char c = dumped[i];
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '\xE2' && i + 2 < dumped.size() && dumped[i + 1] == '\x80' &&
               (dumped[i + 2] == '\xA8' || dumped[i + 2] == '\xA9')) {
      out += dumped[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string ReplayPageHtml(const nlohmann::json& data) {
  std::string title;
  if (data.is_object() && data.contains("title") && data["title"].is_string()) {
    title = data["title"].get<std::string>();
  }
  std::string out(kHead);
  // replay.js sets the same title; this one shows before it runs, and without it
  out += "<title>" + XmlEscaped(title.empty() ? "Replay" : "Replay: " + title) + "</title>\n";
  out += "<style>\n";
  out += ReplayPageStyle();
  out += "</style>\n</head>\n";
  out += kBody;
  out += "<script type=\"application/json\" id=\"replay-data\">";
  out += ScriptSafeJson(data);
  out += "</script>\n<script>\n";
  out += ReplayPageScript();
  out += "</script>\n</body>\n</html>\n";
  return out;
}

void WriteReplayPage(const nlohmann::json& data, const std::string& path) {
  const std::string html = ReplayPageHtml(data);
  try {
    WriteTextFile(path, html);
  } catch (const std::filesystem::filesystem_error& error) {
    throw InputError(path + ": cannot write file (" + error.code().message() + ")");
  }
}

}  // namespace unimouse
