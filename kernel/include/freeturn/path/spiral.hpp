#pragma once
// Spiral tool paths for slow-tool-servo turning (paper 000).
//
// The spiral lives on a base surface of revolution about z, as s = s_e − bθ from the
// aperture's edge to its centre (or the reverse), with s the arc length of the base's
// generating curve and b = pitch/2π; each base point is moved along the base normal to
// the design surface (ray intersection warm-started from the previous point). A plane
// base is the traditional Archimedean spiral r = r_e − bθ projected along z: the code is
// the same, and the plane's projection is the sag itself.

#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/contact_point.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct SpiralOptions {
  double pitch = 0.01;  // mm per revolution, along the base's generating curve
  double outer_radius = 0, inner_radius = 0;  // aperture (mm), measured on the base
  bool centre_to_edge = false;
  // The tool whose programmed point the machine moves (cutter_points.hpp): the chord
  // error is measured on that motion; tool.nose_radius also gives the scallop.
  ToolMotion tool;
  CutterPointOptions points;
  // Threads that plan bands of the spiral at once (0: the hardware's). The bands are fixed
  // by the path alone, so the points are the same on any number.
  int threads = 1;
  // Tests only: every PVT seam has its later band planned again from the seam's blocks, as
  // a seam whose segments miss the target does (spiral.cpp). No natural case was found to
  // miss, so this is how that path is run.
  bool replan_every_seam = false;
  // Tests only: every segment on a creased design measured with the crease searches and
  // the slide, including those whose nose stays clear of every crease (path_stepper.hpp,
  // "Segments clear of creases"), which are otherwise measured as on a smooth design.
  bool measure_every_crease = false;
  // Tests only: a segment measured in full takes every sample of its grid, none left out
  // where its peak cannot lie (path_stepper.hpp, Pruning).
  bool take_every_sample = false;
};

// Streams the contact points into `sink` and returns the summary. Throws InputError
// naming θ and r when a projection misses the design surface, and for bad options.
PathSummary plan_spiral(const Surface& design, const BaseSurface& base,
                        const SpiralOptions& options, ContactSink& sink);

}  // namespace freeturn
