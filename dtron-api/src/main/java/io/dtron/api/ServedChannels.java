package io.dtron.api;

import java.util.Collection;
import java.util.Collections;
import java.util.Objects;
import java.util.Set;
import java.util.TreeSet;

/**
 * The channels one member of the bus serves, as it said in the handshake: those it receives (has a listener for,
 * so it applies a tester's inputs on them) and those it sends (a tester's outputs). A tester that takes part in a
 * run another tester starts says so too, and a tester says that it is one (the channels it names are those it
 * tests). Immutable; names are sorted.
 *
 * @param member   the member's id
 * @param receives the channels it listens to
 * @param sends    the channels it publishes
 * @param joinsRun whether the member is a tester ready to join the next run another tester starts
 * @param tester   whether the member is a tester that starts runs (it serves none of these channels)
 */
public record ServedChannels(String member, Set<String> receives, Set<String> sends, boolean joinsRun,
        boolean tester) {

    /** Copies the sets into sorted, unmodifiable ones. */
    public ServedChannels {
        Objects.requireNonNull(member, "member");
        receives = sortedCopy(receives);
        sends = sortedCopy(sends);
    }

    /** The channels of a member that is no tester. */
    public ServedChannels(String member, Set<String> receives, Set<String> sends) {
        this(member, receives, sends, false, false);
    }

    /** The channels of a member that is no tester starting runs, but may be one joining them. */
    public ServedChannels(String member, Set<String> receives, Set<String> sends, boolean joinsRun) {
        this(member, receives, sends, joinsRun, false);
    }

    private static Set<String> sortedCopy(Collection<String> names) {
        Set<String> copy = new TreeSet<>();
        for (String name : names) {
            copy.add(Objects.requireNonNull(name, "channel name"));
        }
        return Collections.unmodifiableSet(copy);
    }
}
