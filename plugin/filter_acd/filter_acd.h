/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
#ifndef FILTER_ACD_H
#define FILTER_ACD_H

#include <common/plugins/interfaces/filter_plugin.h>

#include <acd/decompose3/decompose.h>
#include <acd/prepare/prepare_solid.h>
#include <acd/solid/solid.h>
#include <acd/structure/collision_hulls.h>

class FilterACD : public QObject, public FilterPlugin
{
	Q_OBJECT
	MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
	Q_INTERFACES(FilterPlugin)

public:
	enum FilterIds { NOTCH_CONCAVITY, CONVEX_DECOMPOSITION, POLYGON_DECOMPOSITION, LEVEL_OF_DETAIL, SKELETON, HULL_UNION };

	FilterACD();

	QString      pluginName() const;
	QString      filterName(ActionIDType filter) const;
	QString      pythonFilterName(ActionIDType f) const;
	QString      filterInfo(ActionIDType filter) const;
	FilterClass  getClass(const QAction* a) const;
	// The level of detail reads a saved tree: it needs no layer.
	FilterArity  filterArity(const QAction* a) const { return ID(a) == LEVEL_OF_DETAIL ? NONE : SINGLE_MESH; }
	int          getPreConditions(const QAction*) const;
	int          getRequirements(const QAction* a);
	int          postCondition(const QAction* a) const;
	RichParameterList initParameterList(const QAction*, const MeshModel& m);
	std::map<std::string, QVariant> applyFilter(
		const QAction*           action,
		const RichParameterList& params,
		MeshDocument&            md,
		unsigned int&            postConditionMask,
		vcg::CallBackPos*        cb);

private:
	// The 3D decomposition as the filters that build on it run it: input checks, preprocessing,
	// options from the shared parameters, log lines.
	struct Run
	{
		acd::PreparedSolid    prepared;   // the solid decomposed, and how it was made from the input
		acd::DecomposeOptions options;
		double                size = 0;
		acd::Decomposition    d;
		std::string           fallback;   // why the solid as given was wrapped after all
	};
	Run  runDecomposition(const RichParameterList& par, MeshModel& input, vcg::CallBackPos* cb);
	void log_prepared(const acd::PreparedSolid& p);
	void log_budget(const acd::CollisionHulls& hulls, double hull_distance);
	std::map<std::string, QVariant> notchConcavity(MeshModel& m, vcg::CallBackPos* cb);
	std::map<std::string, QVariant>
	decompose(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant> skeleton(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant> hullUnion(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant>
	levelOfDetail(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant>
	decomposePolygon(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
};

#endif
