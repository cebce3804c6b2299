package io.dtron.engine;

import java.util.List;

/**
 * What a {@link Steering steered} run found: its goals, and the edges of the model covered on inputs and outputs
 * (of those the exploration before the run found reachable on them).
 *
 * @param goals                    each goal and where it stands
 * @param explored                 whether the exploration before the run saw every reachable state: then a goal
 *                                 found unreachable is proved so
 * @param edgesCovered             edges taken on an input or output (possibly: some state the system may have been
 *                                 in took it)
 * @param edges                    reachable edges on inputs and outputs
 * @param environmentEdgesCovered  of those, the environment's covered
 * @param environmentEdges         of those, the environment's
 * @param environmentCoveredMicros when the last of the environment's was covered, in microseconds since the start;
 *                                 -1 if not all were
 * @param environmentCoveredInputs after how many inputs; -1 if not all were
 */
public record SteeringReport(List<GoalStatus> goals, boolean explored, int edgesCovered, int edges,
                             int environmentEdgesCovered, int environmentEdges, long environmentCoveredMicros,
                             int environmentCoveredInputs) {
    public SteeringReport {
        goals = List.copyOf(goals);
    }
}
