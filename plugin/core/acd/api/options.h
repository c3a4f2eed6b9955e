// The options a user sets, in one table: each one's name (the filter parameter, the command line's
// --name and the Python keyword), dialog title, help, default, and for a choice its labels. The MeshLab
// filter declares its parameters from it and acd_run reads its defaults from it.
#pragma once

#include "acd/decompose3/decompose.h"
#include "acd/hull/bounded_hull.h"
#include "acd/prepare/prepare_solid.h"

#include <string>
#include <vector>

namespace acd {

struct OptionChoice
{
	const char* label;
	int         value;   // the enum's value
	const char* help;
};

struct Option
{
	enum Kind { Number, Integer, Flag, Choice };
	const char*               name;
	Kind                      kind;
	double                    value;   // the default: a number, an integer, 0/1, or the default choice's value
	const char*               title;
	const char*               help;
	std::vector<OptionChoice> choices;   // in menu order (.mlx files store the index)
	int                       index_of(int value) const;   // menu index of a choice's value (-1: none)
	int                       value_of(const std::string& label) const;   // -1: no such label
	std::string               labels() const;   // "a | b | c"
	std::string               full_help() const;   // the help, then each choice's label and help
};

// The decomposition's options, in the dialog's order.
const std::vector<Option>& decomposition_options();
// One of them by name (throws Error(InvalidOption) for an unknown name).
const Option& option(const std::string& name);

enum class TauUnit { PercentOfSize, ModelUnits };

} // namespace acd
