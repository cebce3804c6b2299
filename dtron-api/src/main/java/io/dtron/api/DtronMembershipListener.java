package io.dtron.api;

import java.util.List;

/**
 * Learns when members join or leave a {@link Dtron}'s bus: a member that closes its {@code Dtron}, or whose
 * process dies (noticed by failure detection within a few seconds), leaves.
 */
@FunctionalInterface
public interface DtronMembershipListener {

    /**
     * Called after the members changed.
     *
     * @param members the members now, oldest first; immutable
     * @param joined  the members that joined since the previous change; immutable
     * @param left    the members that left since the previous change; immutable
     */
    void membershipChanged(List<String> members, List<String> joined, List<String> left);
}
