"""One table of defaults for every Python entry point: the CLI's subcommands, the batch runner and
convex_decomposition all start from these values, which are the filter's own (tests compare them option by
option). The labels of each choice are read from the plugin, whose options table declares them."""

DEFAULTS = dict(
    tau=2.5,                        # concavity tolerance, % of the size (tau_unit) or model units
    tau_unit="percent_of_size",
    cut_plane_selection="bisector_or_face",   # bisector_or_face | best | bisector | min_section
    max_parts=0,                    # 0: no limit
    merge_parts=True,               # merge neighbouring parts while their union stays within tau
    merge_measure="hull_distance",  # hull_distance (its hull within tau of it) | concavity (also every notch)
    cut_search="thorough",          # fast (one cut tree, the paper's greedy) | thorough (two, the fewer parts kept)
    max_hull_vertices=0,            # per collision hull; 0: the exact hull
    engine="none",                  # none | mujoco | pybullet | physx | physx_gpu | unity: hulls within its limits
    preprocessing="auto",           # as given if a valid solid, else welded, else holes filled, else alpha-wrapped
    wrap_alpha=2.0,                 # alpha wrap: alpha, % of the size
    wrap_offset=0.1,                # alpha wrap: offset, % of the size
    time_limit=0.0,                 # seconds in the core; 0: none
    hole_handling="best_plane",     # cavities: best_plane | principal_plane | keep_cavities
    hole_order="first",             # cavities before notches (the paper) | by_concavity
    on_self_intersection="warn",    # warn | refuse
    threads=0,                      # threads one decomposition may use; 0: every core (same parts for any)
)

import argparse

# Help text per option, shared by the subcommands that take it.
HELP = dict(
    tau="concavity tolerance: every part's hull lies within tau of the part (%% of the size, or model units "
        "with --tau-unit model_units)",
    tau_unit="unit of --tau",
    cut_plane_selection="how the plane through the most concave notch is chosen",
    max_parts="stop after this many parts (0: no limit; some parts may then exceed tau)",
    merge_parts="merge neighbouring parts while their union stays within tau (--no-merge-parts: the cut "
                "tree's leaves as they are)",
    merge_measure="what a union must stay within tau by to be merged: hull_distance, its hull's distance to it "
                  "(a pocket the hull spans, such as a slot narrower than tau, may stay in one part, which is "
                  "then not cut either; parts of separate solids of the input merge where one hull stays within "
                  "tau of both); concavity, "
                  "that and every notch's concavity (the cuts' own measure: more parts)",
    cut_search="thorough: grow the cut tree twice, cuts picked by the worse part's concavity (the paper) and by "
               "the parts both parts are estimated to need (also trying the planes across the part's principal axes), and "
               "keep the one with fewer parts (about twice the "
               "time; a mesh of over 30,000 faces grows both on its simplified copy and certifies the better); fast: "
               "the first alone",
    max_hull_vertices="at most this many vertices per collision hull, on top of --engine's limits (0: none); a "
                      "reduced hull still contains its part",
    engine="make every collision hull meet this physics engine's limits (PhysX 255 vertices/255 polygons, its GPU "
           "path 64/64, Unity 255 triangles) while still containing its part; the summary says how far the "
           "reduced hulls reach beyond the exact ones",
    preprocessing="auto: as given if the mesh is a valid solid, else welded, else its holes filled, else "
                  "alpha-wrapped; alpha_wrap: always wrapped; none: refuse what is not a closed solid",
    wrap_alpha="alpha wrap: alpha, %% of the size (larger bridges bigger holes)",
    wrap_offset="alpha wrap: offset, %% of the size",
    time_limit="stop cutting after this many seconds (0: none)",
    hole_handling="how cavities (closed inner shells) are resolved",
    hole_order="cut cavities before notches (the paper) or in turn by concavity",
    on_self_intersection="a mesh that crosses itself: decompose with a warning, or refuse",
    threads="threads one decomposition may use (0: every core; a batch gives each mesh its share of them); "
            "the parts are the same for any count",
)

import functools
import re

FILTER = "generate_approximate_convex_decomposition"


@functools.lru_cache(maxsize=None)
def choices(name):
    """The labels the filter accepts for option `name`, in menu order, as the plugin's options table
    declares them (pymeshlab lists them when it refuses a label)."""
    import pymeshlab
    from . import load
    load()
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                               face_matrix=[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    try:
        getattr(ms, FILTER)(**{name: "?"})
    except pymeshlab.InvalidEnumException as e:
        return tuple(re.findall(r"'([^']*)'", str(e).split("Possible values are", 1)[1]))
    raise ValueError(f"{name} is not a choice of {FILTER}")


def add_arguments(parser, *names):
    """Add the named options to an argparse parser, with the shared default, choices and help."""
    for name in names:
        default = DEFAULTS[name]
        kw = dict(default=default, help=HELP[name])
        if isinstance(default, str):
            kw["choices"] = choices(name)
        elif isinstance(default, bool):
            kw["action"] = argparse.BooleanOptionalAction
        else:
            kw["type"] = type(default)
        parser.add_argument("--" + name.replace("_", "-"), **kw)
