/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
// The plugin declares and dispatches: filters, their descriptions and parameters (parameters.cpp);
// each filter's work is in filter_acd_run.cpp. Every exception becomes MLException (the GUI catches
// nothing else).

#include "filter_acd.h"
#include "messages.h"
#include "parameters.h"

#include <acd/decompose3/decompose.h>
#include <acd/structure/level_of_detail.h>
#include <acd/solid/solid.h>

namespace {

const char* kCitation =
	"<br><br>Method: <i>Jyh-Ming Lien, Nancy M. Amato</i>, <b>\"Approximate Convex Decomposition of "
	"Polyhedra\"</b>, ACM Symposium on Solid and Physical Modeling 2007 (Texas A&amp;M TR05-001).";

// Runs `fn`, converting whatever the core or CGAL throws into MLException.
template <class Fn> auto guarded(Fn fn) -> decltype(fn())
{
	try {
		return fn();
	}
	catch (const MLException&) {
		throw;
	}
	catch (const std::bad_alloc&) {
		throw MLException("Out of memory during the convex decomposition.");
	}
	catch (const acd::Error& e) {
		throw MLException(acdml::message(e));
	}
	catch (const std::exception& e) {
		throw MLException(QString("Internal error in the convex decomposition: ") + e.what());
	}
	catch (...) {
		throw MLException("Internal error in the convex decomposition (unknown exception).");
	}
}

} // namespace

FilterACD::FilterACD()
{
	typeList = {NOTCH_CONCAVITY, CONVEX_DECOMPOSITION, POLYGON_DECOMPOSITION, LEVEL_OF_DETAIL, SKELETON, HULL_UNION};
	for (ActionIDType tt : types()) actionList.push_back(new QAction(filterName(tt), this));
}

QString FilterACD::pluginName() const { return "FilterACD"; }

QString FilterACD::filterName(ActionIDType f) const
{
	switch (f) {
	case NOTCH_CONCAVITY: return "Convex Decomposition: Notch Concavity";
	case CONVEX_DECOMPOSITION: return "Convex Decomposition: Approximate Convex Decomposition";
	case POLYGON_DECOMPOSITION: return "Convex Decomposition: Approximate Convex Decomposition of a Polygon";
	case LEVEL_OF_DETAIL: return "Convex Decomposition: Level of Detail from a Saved Tree";
	case SKELETON: return "Convex Decomposition: Skeleton";
	case HULL_UNION: return "Convex Decomposition: Union of Part Hulls (Simplification)";
	default: assert(0); return QString();
	}
}

QString FilterACD::pythonFilterName(ActionIDType f) const
{
	switch (f) {
	case NOTCH_CONCAVITY: return "compute_scalar_by_notch_concavity";
	case CONVEX_DECOMPOSITION: return "generate_approximate_convex_decomposition";
	case POLYGON_DECOMPOSITION: return "generate_polygon_approximate_convex_decomposition";
	case LEVEL_OF_DETAIL: return "generate_convex_decomposition_level_of_detail";
	case SKELETON: return "generate_skeleton_from_convex_decomposition";
	case HULL_UNION: return "generate_convex_hull_union";
	default: assert(0); return QString();
	}
}

QString FilterACD::filterInfo(ActionIDType f) const
{
	switch (f) {
	case NOTCH_CONCAVITY:
		return QString("Measures how concave the mesh is at each notch (reflex edge), as the distance from the "
		               "notch to the <i>bridge</i> (a convex-hull facet not on the surface) of the <i>pocket</i> "
		               "that holds it; notches are assigned to bridges by shortest surface paths between the "
		               "ends of each bridge edge. Stores the concavity (absolute model units) as vertex quality "
		               "and colours it. The mesh must be closed and 2-manifold.") + kCitation;
	case CONVEX_DECOMPOSITION:
		return QString("Splits a closed 2-manifold mesh (any genus) into parts whose concavity is at most "
		               "<i>tau</i>: the most concave notch is cut by a plane through it, splitting the part "
		               "into exactly two closed parts, until every part is tau-convex. Each part becomes a new "
		               "layer named by its path in the binary cut tree (acd_0, acd_00, acd_01, ...). The input "
		               "layer is not modified. The whole tree is returned as JSON.") + kCitation;
	case POLYGON_DECOMPOSITION:
		return QString("Splits a planar polygon with holes into pieces whose concavity is at most <i>tau</i> "
		               "(the paper's 2D algorithm): a notch's concavity is its distance to the bridge line of "
		               "its pocket on the outer boundary's hull; the most concave notch is cut from the notch "
		               "into the polygon, holes are cut along their principal axis. The polygon is the "
		               "boundary of a planar triangle mesh (its boundary loops are the outline and the holes) "
		               "or a layer of edges forming closed loops, in any plane. Each piece becomes a layer "
		               "(a triangulated planar face mesh with its outline as edges) named by its tree path.") +
		       kCitation;
	case LEVEL_OF_DETAIL:
		return QString("Reads the cut tree saved by the 3D decomposition (its <i>tree_file</i>) and adds the parts "
		               "of a coarser level without recomputing anything: the tree is cut where every part's "
		               "concavity is at most the given tau (at least the tau it was computed with), or at a "
		               "given depth. Each part is rebuilt from the saved leaves below it; its saved convex hull "
		               "can be added too.") + kCitation;
	case SKELETON:
		return QString("Decomposes the mesh (same parameters as the decomposition) and extracts a skeleton from "
		               "its tree, top down (the paper's Section 7): a node's skeleton is the principal axis of "
		               "its convex hull, clipped to the node's solid; where that axis leaves the solid or runs "
		               "off-centre, the node's cut splits it (a leaf is split across its axis), and the two "
		               "sides' skeletons are joined through the centre of each cross-section of the cut. "
		               "The default cut (min_section) goes through the neck at each notch, so surface noise "
		               "hardly moves the skeleton. Output: an edge-mesh layer coloured by piece.") +
		       kCitation;
	case HULL_UNION:
		return QString("Decomposes the mesh and simplifies it by the union of its parts' convex hulls (the "
		               "paper's Figure 18): one layer per hull (optionally at most N vertices, as physics "
		               "engines need) and one merged layer, either the hulls together (overlapping shells) or "
		               "their true boolean union (CGAL corefinement, exact constructions). Reports the face "
		               "count reduction and the volume IoU between the union and the mesh.") +
		       kCitation;
	default: assert(0); return QString();
	}
}

FilterPlugin::FilterClass FilterACD::getClass(const QAction* a) const
{
	switch (ID(a)) {
	case NOTCH_CONCAVITY: return FilterClass(Quality + Measure);
	case CONVEX_DECOMPOSITION:
	case POLYGON_DECOMPOSITION:
	case LEVEL_OF_DETAIL:
	case SKELETON:
	case HULL_UNION: return FilterClass(Remeshing + Layer);
	default: assert(0); return Generic;
	}
}

int FilterACD::getPreConditions(const QAction* a) const
{
	// A point cloud is valid input for the decomposition with preprocessing = alpha_wrap.
	return ID(a) == NOTCH_CONCAVITY ? MeshModel::MM_FACENUMBER : MeshModel::MM_NONE;
}

int FilterACD::getRequirements(const QAction* a)
{
	return ID(a) == NOTCH_CONCAVITY ? MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR : MeshModel::MM_NONE;
}

int FilterACD::postCondition(const QAction* a) const
{
	// The decomposition only adds layers.
	return ID(a) == NOTCH_CONCAVITY ? MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR : MeshModel::MM_NONE;
}

RichParameterList FilterACD::initParameterList(const QAction* a, const MeshModel& /*m*/)
{
	RichParameterList p;
	switch (ID(a)) {
	case NOTCH_CONCAVITY: return p;
	case POLYGON_DECOMPOSITION: acdml::add_polygon_parameters(p); return p;
	case LEVEL_OF_DETAIL: acdml::add_level_of_detail_parameters(p); return p;
	case SKELETON:
		acdml::add_decomposition_parameters(p, {3.0, "min_section", false, false, false});
		p.addParam(RichInt("max_refinement", 3, "Skeleton: refinement depth",
		                   "A part whose axis leaves it or runs off-centre is split across its axis, at most "
		                   "this many times over (0 = never)."));
		p.addParam(RichFloat("off_centre", 0.2, "Skeleton: off-centre limit",
		                     "Split a piece when the middle of its axis chord is farther than this fraction of "
		                     "the chord's length from its hull's centroid, or when, at stations along the chord, "
		                     "the chord is farther than this fraction of the solid's width across it from the "
		                     "middle of that width (the chord runs along one side of a bent piece)."));
		return p;
	case HULL_UNION:
		acdml::add_decomposition_parameters(p, {5.0, nullptr, false, true, true});
		p.addParam(RichEnum("merge", 0, QStringList{"together", "boolean_union"}, "Merged layer",
		                    "together: the hulls in one layer (overlapping shells; fast); boolean_union: their true "
		                    "union by CGAL corefinement with exact constructions (one closed surface; slower)."));
		p.addParam(RichInt("iou_samples", 200000, "IoU samples",
		                   "Monte Carlo samples for the volume IoU between the union and the mesh."));
		return p;
	default:
		acdml::add_decomposition_parameters(p, {-1, nullptr, true, true, true});
		p.addParam(RichString("tree_file", "", "Save tree as (JSON)",
		                      "If set, the whole cut tree (nodes, parents, paths, planes, concavity, volume) is "
		                      "written to this JSON file; layer names are the leaves' paths. Empty: not written.",
		                      true));
		return p;
	}
}

std::map<std::string, QVariant> FilterACD::applyFilter(
	const QAction*           action,
	const RichParameterList& par,
	MeshDocument&            md,
	unsigned int& /*postConditionMask*/,
	vcg::CallBackPos* cb)
{
	switch (ID(action)) {
	case NOTCH_CONCAVITY: return guarded([&] { return notchConcavity(*md.mm(), cb); });
	case CONVEX_DECOMPOSITION: return guarded([&] { return decompose(par, md, cb); });
	case POLYGON_DECOMPOSITION: return guarded([&] { return decomposePolygon(par, md, cb); });
	case LEVEL_OF_DETAIL: return guarded([&] { return levelOfDetail(par, md, cb); });
	case SKELETON: return guarded([&] { return skeleton(par, md, cb); });
	case HULL_UNION: return guarded([&] { return hullUnion(par, md, cb); });
	default: wrongActionCalled(action);
	}
	return {};
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterACD)
