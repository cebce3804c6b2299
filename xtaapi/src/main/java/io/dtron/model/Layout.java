package io.dtron.model;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.ModelSyntax;
import io.dtron.xta.Parsed;
import io.dtron.xta.ast.Coord;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Nta;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;

/**
 * The drawing of a model's templates as the Uppaal editor saved it: where each location, each edge's bend points
 * (nails) and each label sit. Locations and edges are numbered as in the {@link Process}es of the loaded {@link
 * Network} ({@code Location#index}, {@code Edge#index}), so a report can colour what a run covered. A model without
 * positions (an {@code .xta} file) has a layout whose points are null. Immutable.
 *
 * @param templates the templates, in the order of the file
 */
public record Layout(List<Template> templates) {
    public Layout {
        templates = List.copyOf(templates);
    }

    /** A point of the editor's canvas (y grows downward). */
    public record Point(int x, int y) {
    }

    /**
     * A label as drawn.
     *
     * @param kind {@code name}, {@code invariant}, {@code guard}, {@code synchronisation}, {@code assignment},
     *             {@code select}, {@code comments}...
     * @param text its text as written
     * @param at   where it is drawn, or null when the model does not say
     */
    public record Label(String kind, String text, Point at) {
    }

    /**
     * A location.
     *
     * @param name    its name ({@code _id3} for an anonymous one, as the loaded network calls it)
     * @param kind    {@code normal}, {@code urgent}, {@code committed} or {@code branchpoint}
     * @param initial whether it is the template's initial location
     * @param at      its centre, or null
     * @param labels  its labels (name, invariant...)
     */
    public record Location(String name, String kind, boolean initial, Point at, List<Label> labels) {
        public Location {
            labels = List.copyOf(labels);
        }
    }

    /**
     * An edge.
     *
     * @param source the source location's index
     * @param target the target location's index
     * @param nails  its bend points, from source to target
     * @param labels its labels (select, guard, synchronisation, assignment)
     */
    public record Edge(int source, int target, List<Point> nails, List<Label> labels) {
        public Edge {
            nails = List.copyOf(nails);
            labels = List.copyOf(labels);
        }
    }

    /**
     * A template's drawing.
     *
     * @param name      its name
     * @param locations its locations, numbered as the network's
     * @param edges     its edges, numbered as the network's
     */
    public record Template(String name, List<Location> locations, List<Edge> edges) {
        public Template {
            locations = List.copyOf(locations);
            edges = List.copyOf(edges);
        }

        /** Whether every location has a saved position. */
        public boolean positioned() {
            return !locations.isEmpty() && locations.stream().allMatch(l -> l.at() != null
                    || l.kind().equals("branchpoint"));
        }
    }

    /** The template called {@code name}. */
    public Optional<Template> template(String name) {
        return templates.stream().filter(t -> t.name().equals(name)).findFirst();
    }

    /**
     * The layout of the model file {@code file}.
     *
     * @throws ModelException if it cannot be read or does not parse
     */
    public static Layout read(Path file) throws ModelException {
        String text;
        try {
            text = ModelSyntax.decode(Files.readAllBytes(file));
        } catch (IOException e) {
            throw new ModelException(List.of(Diagnostic.fileError(file.toString(), "cannot read the file: "
                    + e.getMessage())));
        }
        return of(file.toString(), text);
    }

    /**
     * The layout of a model's text; {@code name} is used in messages.
     *
     * @throws ModelException if it does not parse
     */
    public static Layout of(String name, String text) throws ModelException {
        Parsed<Nta> parsed = ModelSyntax.parseModel(name, text);
        if (parsed.hasErrors()) {
            throw new ModelException(parsed.diagnostics());
        }
        List<Template> templates = new ArrayList<>();
        for (Decl.Template t : parsed.value().templates()) {
            templates.add(template(t));
        }
        return new Layout(templates);
    }

    private static Template template(Decl.Template t) {
        Map<String, Integer> byId = new HashMap<>();
        List<Location> locations = new ArrayList<>();
        for (io.dtron.xta.ast.Location l : t.locations()) {
            byId.putIfAbsent(l.id(), locations.size());
            List<Label> labels = new ArrayList<>();
            for (io.dtron.xta.ast.Label label : l.labels()) {
                labels.add(new Label(label.kind(), label.text(), point(label.coord())));
            }
            if (labels.isEmpty() && l.invariant() != null) {
                labels.add(new Label("invariant", l.invariant().pos().text(), null));
            }
            locations.add(new Location(l.name() != null ? l.name() : "_" + l.id(), l.kind().name()
                    .toLowerCase(Locale.ROOT), l.id().equals(t.init()), point(l.coord()), labels));
        }
        for (String id : t.branchpoints()) {
            byId.putIfAbsent(id, locations.size());
            locations.add(new Location("_" + id, "branchpoint", false, null, List.of()));
        }
        List<Edge> edges = new ArrayList<>();
        for (io.dtron.xta.ast.Edge e : t.edges()) {
            Integer source = byId.get(e.source());
            Integer target = byId.get(e.target());
            if (source == null || target == null) {
                continue; // the loader rejects such a model
            }
            List<Point> nails = e.nails().stream().map(Layout::point).toList();
            List<Label> labels = new ArrayList<>();
            for (io.dtron.xta.ast.Label label : e.labels()) {
                labels.add(new Label(label.kind(), label.text(), point(label.coord())));
            }
            if (labels.isEmpty()) {
                labels.addAll(written(e));
            }
            edges.add(new Edge(source, target, nails, labels));
        }
        return new Template(t.name(), locations, edges);
    }

    /** The labels of an edge of a textual model, from its parts as written. */
    private static List<Label> written(io.dtron.xta.ast.Edge e) {
        List<Label> labels = new ArrayList<>();
        if (!e.selects().isEmpty()) {
            labels.add(new Label("select", String.join(", ", e.selects().stream().map(s -> s.pos().text())
                    .toList()), null));
        }
        if (e.guard() != null) {
            labels.add(new Label("guard", e.guard().pos().text(), null));
        }
        if (e.sync() != null) {
            labels.add(new Label("synchronisation", e.sync().pos().text(), null));
        }
        if (!e.updates().isEmpty()) {
            labels.add(new Label("assignment", String.join(", ", e.updates().stream().map(u -> u.pos().text())
                    .toList()), null));
        }
        return labels;
    }

    private static Point point(Coord c) {
        return c == null ? null : new Point(c.x(), c.y());
    }
}
