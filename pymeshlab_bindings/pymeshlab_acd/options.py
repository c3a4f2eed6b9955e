"""One table of defaults for every entry point: the CLI's subcommands, the batch runner and
convex_decomposition all start from these values (the filters keep MeshLab's own parameter defaults)."""

DEFAULTS = dict(
    tau=2.5,                        # concavity tolerance, % of the size (tau_unit) or model units
    tau_unit="percent_of_size",
    cut_plane_selection="bisector_or_face",   # bisector_or_face | best | bisector | min_section
    max_parts=0,                    # 0: no limit
    merge_parts=True,               # merge neighbouring parts while their union stays within tau
    max_hull_vertices=0,            # per collision hull; 0: the exact hull
    preprocessing="auto",           # as given if a valid solid, else welded, else alpha-wrapped
    wrap_alpha=2.0,                 # alpha wrap: alpha, % of the size
    wrap_offset=0.1,                # alpha wrap: offset, % of the size
    time_limit=0.0,                 # seconds in the core; 0: none
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
    max_hull_vertices="per collision hull (0: exact hulls; 64 suits engines that cap hull sizes)",
    preprocessing="auto: as given if the mesh is a valid solid, else welded, else alpha-wrapped; alpha_wrap: "
                  "always wrapped; none: refuse what is not a closed solid",
    wrap_alpha="alpha wrap: alpha, %% of the size (larger bridges bigger holes)",
    wrap_offset="alpha wrap: offset, %% of the size",
    time_limit="stop cutting after this many seconds (0: none)",
)

CHOICES = dict(tau_unit=["percent_of_size", "model_units"], cut_plane_selection=["best", "bisector", "min_section", "bisector_or_face"],
               preprocessing=["auto", "none", "alpha_wrap"])


def add_arguments(parser, *names):
    """Add the named options to an argparse parser, with the shared default, choices and help."""
    for name in names:
        default = DEFAULTS[name]
        kw = dict(default=default, help=HELP[name])
        if name in CHOICES:
            kw["choices"] = CHOICES[name]
        elif isinstance(default, bool):
            kw["action"] = argparse.BooleanOptionalAction
        elif not isinstance(default, str):
            kw["type"] = type(default)
        parser.add_argument("--" + name.replace("_", "-"), **kw)
