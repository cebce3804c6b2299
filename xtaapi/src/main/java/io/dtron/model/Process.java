package io.dtron.model;

import java.util.List;

/**
 * A process of the network: one instance of a template.
 *
 * @param index     its number in {@link Network#processes()}
 * @param name      its name ({@code Gate}, {@code Train(2)})
 * @param template  the template it instantiates
 * @param locations its locations
 * @param initial   the index of its initial location
 * @param edges     its edges
 * @param priority  its priority level from the system line (0 is lowest)
 */
public record Process(int index, String name, String template, List<Location> locations, int initial,
                      List<Edge> edges, int priority) {
    public Process {
        locations = List.copyOf(locations);
        edges = List.copyOf(edges);
    }

    /** The location called {@code name}, or null. */
    public Location location(String name) {
        return locations.stream().filter(l -> l.name().equals(name)).findFirst().orElse(null);
    }
}
