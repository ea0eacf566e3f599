#include "gridtopo/topology/mrpt_graph.h"

namespace gridtopo::topology {

mrpt::graphs::CNetworkOfPoses2D toMrptPoseGraph(const TopologicalGraph& g) {
  mrpt::graphs::CNetworkOfPoses2D out;
  for (const auto& n : g.nodes)
    out.nodes[static_cast<mrpt::graphs::TNodeID>(n.id)] = mrpt::poses::CPose2D(n.anchor_m.x, n.anchor_m.y, 0);
  for (const auto& e : g.edges) {
    const GraphNode *a = g.node(e.a), *b = g.node(e.b);
    if (!a || !b) continue;
    const mrpt::poses::CPose2D pa(a->anchor_m.x, a->anchor_m.y, 0), pb(b->anchor_m.x, b->anchor_m.y, 0);
    out.insertEdge(static_cast<mrpt::graphs::TNodeID>(e.a), static_cast<mrpt::graphs::TNodeID>(e.b), pb - pa);
  }
  return out;
}

}  // namespace gridtopo::topology
