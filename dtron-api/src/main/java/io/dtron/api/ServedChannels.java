package io.dtron.api;

import java.util.Collection;
import java.util.Collections;
import java.util.Objects;
import java.util.Set;
import java.util.TreeSet;

/**
 * The channels one member of the bus serves, as it said in the handshake: those it receives (has a listener for,
 * so it applies a tester's inputs on them) and those it sends (a tester's outputs). Immutable; names are sorted.
 *
 * @param member   the member's id
 * @param receives the channels it listens to
 * @param sends    the channels it publishes
 */
public record ServedChannels(String member, Set<String> receives, Set<String> sends) {

    /** Copies the sets into sorted, unmodifiable ones. */
    public ServedChannels {
        Objects.requireNonNull(member, "member");
        receives = sortedCopy(receives);
        sends = sortedCopy(sends);
    }

    private static Set<String> sortedCopy(Collection<String> names) {
        Set<String> copy = new TreeSet<>();
        for (String name : names) {
            copy.add(Objects.requireNonNull(name, "channel name"));
        }
        return Collections.unmodifiableSet(copy);
    }
}
