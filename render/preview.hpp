#pragma once
// `tilekit texture preview`: one self-contained HTML page that renders the infinite texture live
// with WebGL2, using the same fragment shaders as the headless renderer (glsl_sampler.hpp), with
// the atlas and its mip chain embedded (PNG data URIs), and the exemplar surface when one is given
// (its mip chain, the Gaussianized chain and the look-up table as half floats), so the page can
// switch between tiles, hex and hpn. No network and no server: open the file.
//
// The page computes the view's row table (render/view.hpp) in JavaScript with the same double
// arithmetic as view_rows, and the hash tables of any seed with a port of the seeded shuffle
// (base/random.hpp, tiling/lattice_hash.hpp); at load it checks that port against the tables of
// the page's default seed computed here and shows an error if they differ. The JavaScript is
// render/preview_tables.js (the ports) and render/preview.js (the page), embedded at build time
// (render/preview_scripts.hpp) and tested under node against golden vectors (tests/render/).
//
// Query: ?capture=1&size=WxH&u=U&v=V&scale=S&seed=N&tilt=T[&method=M&aniso=A] shows only the
// canvas, W x H, with that view: (u, v) the texel at the top-left as in `texture render --origin
// U,V`, and scale, seed, tilt, method and aniso as in `texture render`. Without capture=1 the
// same parameters set the starting view of the interactive page (drag to pan, wheel to zoom,
// a slider to tilt, buttons for the method).
#include <string>

#include "render/cpu_renderer.hpp"

namespace tilekit {

// `o` gives the defaults (hash, seed, anisotropy); the hash kind is fixed for the page.
std::string preview_html(const TextureAtlas& atlas, const ExemplarSurface* exemplar, const RenderOptions& o);

}  // namespace tilekit
