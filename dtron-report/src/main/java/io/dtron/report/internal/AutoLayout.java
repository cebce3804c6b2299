package io.dtron.report.internal;

import io.dtron.model.Layout;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Deque;
import java.util.List;

/**
 * A readable drawing of a template that has no saved positions: up to {@link #CIRCLE} locations on a circle, in the
 * order of their distance (in edges) from the initial location, so that no edge crosses a location; more in columns
 * by that distance, the unreachable ones in a last column. Labels are placed by the page.
 */
final class AutoLayout {
    static final int COLUMN = 220;
    static final int ROW = 130;
    static final int CIRCLE = 12;

    private AutoLayout() {
    }

    static Layout.Template of(Layout.Template t) {
        int n = t.locations().size();
        int[] depth = new int[n];
        Arrays.fill(depth, -1);
        Deque<Integer> queue = new ArrayDeque<>();
        for (int i = 0; i < n; i++) {
            if (t.locations().get(i).initial()) {
                depth[i] = 0;
                queue.add(i);
            }
        }
        if (queue.isEmpty() && n > 0) {
            depth[0] = 0;
            queue.add(0);
        }
        int deepest = 0;
        while (!queue.isEmpty()) {
            int at = queue.poll();
            for (Layout.Edge e : t.edges()) {
                if (e.source() == at && depth[e.target()] < 0) {
                    depth[e.target()] = depth[at] + 1;
                    deepest = Math.max(deepest, depth[e.target()]);
                    queue.add(e.target());
                }
            }
        }
        int[] rows = new int[deepest + 2];
        List<Integer> order = new ArrayList<>();
        for (int d = 0; d <= deepest + 1; d++) {
            for (int i = 0; i < n; i++) {
                if ((depth[i] < 0 ? deepest + 1 : depth[i]) == d) {
                    order.add(i);
                }
            }
        }
        double radius = Math.max(110, n * 45);
        List<Layout.Location> locations = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            int column = depth[i] < 0 ? deepest + 1 : depth[i];
            Layout.Location l = t.locations().get(i);
            int row = rows[column]++;
            Layout.Point at;
            if (n <= CIRCLE) {
                // on a circle a straight edge between two locations passes by every other one
                double angle = Math.PI + 2 * Math.PI * order.indexOf(i) / n;
                at = new Layout.Point((int) Math.round(radius + radius * Math.cos(angle)),
                        (int) Math.round(radius + radius * Math.sin(angle)));
            } else {
                // a column's rows alternate a little to the side, so that edges along a column miss locations
                at = new Layout.Point(column * COLUMN + (row % 2) * 40, row * ROW);
            }
            List<Layout.Label> labels = l.labels().stream().map(x -> new Layout.Label(x.kind(), x.text(), null))
                    .toList();
            locations.add(new Layout.Location(l.name(), l.kind(), l.initial(), at, labels));
        }
        List<Layout.Edge> edges = t.edges().stream().map(e -> new Layout.Edge(e.source(), e.target(), List.of(),
                e.labels().stream().map(x -> new Layout.Label(x.kind(), x.text(), null)).toList())).toList();
        return new Layout.Template(t.name(), locations, edges);
    }
}
