// tilekit texture preview: one self-contained HTML page that renders the infinite texture live with
// WebGL2 and the same GLSL as `texture render --glsl` (render/preview.hpp).
#include <fmt/format.h>

#include <memory>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "cli/cmd_texture.hpp"
#include "render/preview.hpp"

namespace tilekit::cli {

namespace {

struct PreviewArgs {
  SourceArgs source;
  std::string out;
};

void run_preview(const PreviewArgs& a, const Context& ctx) {
  if (a.source.atlas.empty()) throw InputError("--atlas is required (written by `tilekit texture atlas`)");
  SourceArgs args = a.source;
  args.method = "tiles";
  const std::unique_ptr<LoadedSource> s = load_source(args);
  const std::string html = preview_html(*s->atlas, s->exemplar ? &*s->exemplar : nullptr, s->options);
  write_file_atomic(a.out, html);
  nlohmann::json j = source_json(*s);
  j.erase("method");
  j.erase("memory_bytes");
  j["methods"] = s->exemplar ? nlohmann::json{"tiles", "hex", "hpn"} : nlohmann::json{"tiles"};
  j["out"] = a.out;
  j["bytes"] = html.size();
  j["levels"] = s->atlas->levels.size();
  emit(ctx, j, [&] {
    fmt::print("{}: {:.1f} MB, self-contained (atlas and {} mip levels embedded{}); methods {}\n", a.out,
               double(html.size()) / 1e6, s->atlas->levels.size() - 1,
               s->exemplar ? ", exemplar " + s->exemplar->name : "", j["methods"].dump());
    fmt::print("open it in a browser with WebGL2; ?capture=1&size=WxH&u=U&v=V&scale=S&seed=N&tilt=T shows one view\n");
  });
}

}  // namespace

void add_texture_preview(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "preview", "One self-contained HTML page rendering the texture live with WebGL2 (pan, zoom, tilt, methods)");
  auto a = std::make_shared<PreviewArgs>();
  add_source_options(cmd, a->source);
  cmd->remove_option(cmd->get_option("--method"));
  cmd->add_option("--out", a->out, "HTML file to write")->required();
  add_json_flag(cmd, ctx);
  cmd->footer(
      "--atlas is required; with --exemplar the page can also show the hex and hpn baselines.\n"
      "Query: ?capture=1&size=WxH&u=U&v=V&scale=S&seed=N&tilt=T[&method=tiles|hex|hpn&aniso=A] shows only the "
      "canvas with that view (u,v: the texel at the top-left, as `texture render --origin U,V`).\n"
      "Exit codes: 0 ok, 1 not found, 2 bad input.");
  cmd->callback([a, &ctx] { run_preview(*a, ctx); });
}

}  // namespace tilekit::cli
