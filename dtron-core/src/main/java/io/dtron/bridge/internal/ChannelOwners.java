package io.dtron.bridge.internal;

import io.dtron.api.ServedChannels;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.TreeSet;

/**
 * Not API. Who owns the output channels of a tester's model: the members that said in the handshake that they send
 * on them (the inputs are the tester's own). An output has one owner, since the tester judges its messages as one system's: two members that say
 * they send it, two members with one id, or a member that sends on it without having said so (while another said
 * it does, or after another member that said nothing sent on it first) are named, one line. The tester's own
 * messages and the members it leaves out (the testers of other runs) own nothing; a member that left owns nothing
 * any more, since the handshake forgets it. Thread-safe.
 */
public final class ChannelOwners {
    private final Set<String> inputs;
    private final Set<String> outputs;
    /** Of the members that said nothing in the handshake, the first that sent on each output in this run. */
    private final Map<String, String> silentSenders = new HashMap<>();

    /**
     * @param inputs  the model's input channels
     * @param outputs the model's output channels
     */
    public ChannelOwners(Set<String> inputs, Set<String> outputs) {
        this.inputs = Set.copyOf(inputs);
        this.outputs = Set.copyOf(outputs);
    }

    /** Forgets the senders seen in the last run. */
    public synchronized void newRun() {
        silentSenders.clear();
    }

    /**
     * Returns what makes the outputs' owners ambiguous now: two members on the bus with one id, or an output that
     * two members say they send; empty when each output has at most one owner.
     *
     * @param members  the members on the bus now, this one included
     * @param served   what the other members said they serve, by member id
     * @param excluded the members that own nothing of this run (this tester, the testers of other runs)
     */
    public Optional<String> conflict(List<String> members, Map<String, ServedChannels> served, Set<String> excluded) {
        Set<String> seen = new TreeSet<>();
        for (String member : members) {
            if (!seen.add(member)) {
                return Optional.of(members.stream().filter(member::equals).count() + " members have the id " + member
                        + ", so the tester cannot tell their messages apart");
            }
        }
        for (String output : new TreeSet<>(outputs)) {
            List<ServedChannels> owners = declaredOwners(output, served, excluded);
            if (owners.size() > 1) {
                return Optional.of(sentByMany(output, owners));
            }
        }
        return Optional.empty();
    }

    /**
     * Checks the sender of a message on an output: returns why it is not the output's one owner, or empty when it
     * is (it alone said it sends the output, or said nothing and is the first such member to send on it while no
     * member says it sends it). Excluded members are not checked.
     */
    public synchronized Optional<String> notOwner(String output, String sender, Map<String, ServedChannels> served,
            Set<String> excluded) {
        if (excluded.contains(sender) || !outputs.contains(output)) {
            return Optional.empty();
        }
        ServedChannels own = served.get(sender);
        List<ServedChannels> owners = declaredOwners(output, served, excluded);
        if (own != null && own.sends().contains(output)) {
            return owners.size() > 1 ? Optional.of(sentByMany(output, owners)) : Optional.empty();
        }
        String what = own == null ? "member " + sender + ", which did not say what it serves,"
                : describe(own) + ", which did not say it sends " + output + ",";
        if (!owners.isEmpty()) {
            return Optional.of(what + " sent output " + output + ", which " + owners.stream()
                    .map(ChannelOwners::describe).reduce((a, b) -> a + " and " + b).orElseThrow() + " sends: the"
                    + " tester cannot judge their messages as one system's");
        }
        if (own != null) {
            return Optional.of(what + " sent output " + output + ": the tester cannot tell which system it stands"
                    + " for");
        }
        String first = silentSenders.putIfAbsent(output, sender);
        if (first == null || first.equals(sender)) {
            return Optional.empty();
        }
        return Optional.of("output " + output + " is sent by 2 members, " + first + " and " + sender + " (neither said"
                + " what it serves), and the tester would judge their messages as one system's");
    }

    /**
     * Why a message on an input from a member other than the tester (and the other testers of its run) spoils the
     * run: an input is the tester's to choose, and the member's message may have been applied as one.
     */
    public static String inputSent(String input, String sender, Map<String, ServedChannels> served) {
        ServedChannels own = served.get(sender);
        return (own == null ? "member " + sender + ", which did not say what it serves," : describe(own)) + " sent input "
                + input + ", which only the tester sends: the system under test may have applied an input the model"
                + " did not choose";
    }

    /**
     * Whether a member serves a channel of the model: it said it receives an input (so applies it) or sends an
     * output.
     */
    public boolean servesTheModel(ServedChannels served) {
        return served.receives().stream().anyMatch(inputs::contains) || served.sends().stream()
                .anyMatch(outputs::contains);
    }

    /** "ticker-a (receives [reset], sends [tick])", with "tester" for a tester. */
    public static String describe(ServedChannels served) {
        String role = served.tester() ? "tester; " : served.joinsRun() ? "tester joining a run; " : "";
        return served.member() + " (" + role + "receives " + served.receives() + ", sends " + served.sends() + ")";
    }

    /** "output tick is sent by 2 members, A (...) and B (...), and ...". */
    private static String sentByMany(String output, List<ServedChannels> owners) {
        List<String> named = owners.stream().map(ChannelOwners::describe).toList();
        return "output " + output + " is sent by " + owners.size() + " members, " + String.join(", ",
                named.subList(0, named.size() - 1)) + " and " + named.get(named.size() - 1) + ", and the tester would"
                + " judge their messages as one system's";
    }

    private static List<ServedChannels> declaredOwners(String output, Map<String, ServedChannels> served,
            Set<String> excluded) {
        List<ServedChannels> owners = new ArrayList<>();
        for (ServedChannels s : served.values()) {
            if (!excluded.contains(s.member()) && s.sends().contains(output)) {
                owners.add(s);
            }
        }
        owners.sort(java.util.Comparator.comparing(ServedChannels::member));
        return owners;
    }
}
