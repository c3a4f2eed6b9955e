/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
#ifndef FILTER_ACD_MESSAGES_H
#define FILTER_ACD_MESSAGES_H

#include <acd/mesh/mesh.h>

#include <QString>

namespace acdml {

// The core's error as MeshLab's log and pymeshlab show it: input problems a MeshLab filter or a
// parameter repairs name that repair; the rest keep the core's words.
QString message(const acd::Error& e);

} // namespace acdml

#endif
