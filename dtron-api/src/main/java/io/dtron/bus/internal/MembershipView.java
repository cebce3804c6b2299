package io.dtron.bus.internal;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * Who is on the bus: an immutable, numbered list of member ids, the same at
 * every member for the same view id.
 */
public final class MembershipView {
    private final long id;
    private final List<String> members;

    /**
     * Creates a view.
     *
     * @param id      the view number; later views have larger numbers
     * @param members the member ids, oldest member first
     */
    public MembershipView(long id, List<String> members) {
        this.id = id;
        this.members = List.copyOf(members);
    }

    /** Returns the view number. */
    public long id() {
        return id;
    }

    /** Returns the member ids, oldest first; immutable. */
    public List<String> members() {
        return members;
    }

    /** Returns the members of this view that were not in {@code previous}. */
    public List<String> joinedSince(MembershipView previous) {
        List<String> joined = new ArrayList<>(members);
        joined.removeAll(previous.members);
        return List.copyOf(joined);
    }

    /** Returns the members of {@code previous} that are not in this view. */
    public List<String> leftSince(MembershipView previous) {
        List<String> left = new ArrayList<>(previous.members);
        left.removeAll(members);
        return List.copyOf(left);
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof MembershipView other && id == other.id && members.equals(other.members);
    }

    @Override
    public int hashCode() {
        return Objects.hash(id, members);
    }

    @Override
    public String toString() {
        return "View#" + id + members;
    }
}
