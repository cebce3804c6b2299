package io.dtron.bridge.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ServedChannels;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import org.junit.jupiter.api.Test;

/** Who owns the ticker model's output {@code tick}, from what members said in the handshake. */
class ChannelOwnersTest {
    private static final ChannelOwners TICKER = new ChannelOwners(Set.of("reset"), Set.of("tick"));
    private static final ServedChannels A = new ServedChannels("ticker-a", Set.of("reset"), Set.of("tick"));
    private static final ServedChannels B = new ServedChannels("ticker-b", Set.of("reset"), Set.of("tick"));
    private static final ServedChannels OBSERVER = new ServedChannels("observer", Set.of("tick", "weather"), Set.of());
    /** A second tester of the same model, refused: it sends the model's input and receives both channels. */
    private static final ServedChannels TESTER = new ServedChannels("tester-2", Set.of("reset", "tick"),
            Set.of("reset"), false, true);
    /** A tester whose input is this model's output (one run of two testers, or another run). */
    private static final ServedChannels PEER = new ServedChannels("peer", Set.of("tick"), Set.of("tick"), true, false);

    private static Map<String, ServedChannels> served(ServedChannels... all) {
        return java.util.Arrays.stream(all).collect(java.util.stream.Collectors.toMap(ServedChannels::member,
                s -> s));
    }

    @Test
    void oneSenderOfEachOutputIsNoConflictWhateverElseIsOnTheBus() {
        assertEquals(Optional.empty(), TICKER.conflict(List.of("me", "ticker-a", "observer", "tester-2"),
                served(A, OBSERVER, TESTER), Set.of("me", "tester-2")));
        // another tester's input that is this model's output: the tester is its one sender
        assertEquals(Optional.empty(), TICKER.conflict(List.of("me", "peer"), served(PEER), Set.of("me")));
    }

    @Test
    void twoSendersOfAnOutputAreNamedWithWhatTheySaidTheyServe() {
        assertEquals(Optional.of("output tick is sent by 2 members, ticker-a (receives [reset], sends [tick]) and"
                + " ticker-b (receives [reset], sends [tick]), and the tester would judge their messages as one"
                + " system's"), TICKER.conflict(List.of("me", "ticker-a", "ticker-b"), served(A, B), Set.of("me")));
        assertTrue(TICKER.conflict(List.of("me", "ticker-a", "peer"), served(A, PEER), Set.of("me")).orElseThrow()
                .contains("peer (tester joining a run; receives [tick], sends [tick])"));
        // a tester of another run owns nothing of this one
        assertEquals(Optional.empty(), TICKER.conflict(List.of("me", "ticker-a", "peer"), served(A, PEER),
                Set.of("me", "peer")));
    }

    @Test
    void twoMembersWithOneIdAreNamed() {
        assertEquals(Optional.of("2 members have the id ticker-a, so the tester cannot tell their messages apart"),
                TICKER.conflict(List.of("me", "ticker-a", "ticker-a"), served(A), Set.of("me")));
    }

    @Test
    void aSenderThatDidNotSaySoIsNamedUnlessNoOneSaidSoAndItWasFirst() {
        ChannelOwners owners = new ChannelOwners(Set.of("reset"), Set.of("tick"));
        assertEquals(Optional.empty(), owners.notOwner("tick", "ticker-a", served(A), Set.of("me")));
        assertEquals(Optional.of("observer (receives [tick, weather], sends []), which did not say it sends tick, sent"
                + " output tick, which ticker-a (receives [reset], sends [tick]) sends: the tester cannot judge their"
                + " messages as one system's"), owners.notOwner("tick", "observer", served(A, OBSERVER), Set.of("me")));
        assertEquals(Optional.of("member old, which did not say what it serves, sent output tick, which ticker-a"
                + " (receives [reset], sends [tick]) sends: the tester cannot judge their messages as one system's"),
                owners.notOwner("tick", "old", served(A), Set.of("me")));
        // of two members that say they send it, neither owns it
        assertTrue(owners.notOwner("tick", "ticker-b", served(A, B), Set.of("me")).orElseThrow()
                .startsWith("output tick is sent by 2 members, ticker-a "));
        // members that say nothing (older adapters, waited for by number): the first to send owns the output
        assertEquals(Optional.empty(), owners.notOwner("tick", "old", Map.of(), Set.of("me")));
        assertEquals(Optional.empty(), owners.notOwner("tick", "old", Map.of(), Set.of("me")));
        assertEquals(Optional.of("output tick is sent by 2 members, old and older (neither said what it serves), and"
                + " the tester would judge their messages as one system's"),
                owners.notOwner("tick", "older", Map.of(), Set.of("me")));
        owners.newRun();
        assertEquals(Optional.empty(), owners.notOwner("tick", "older", Map.of(), Set.of("me")));
        // the tester's own messages, and inputs, are not checked
        assertEquals(Optional.empty(), owners.notOwner("tick", "me", served(A), Set.of("me")));
        assertEquals(Optional.empty(), owners.notOwner("reset", "observer", served(A, OBSERVER), Set.of("me")));
    }

    @Test
    void aMemberServesTheModelByReceivingAnInputOrSendingAnOutput() {
        assertTrue(TICKER.servesTheModel(A));
        assertTrue(TICKER.servesTheModel(new ServedChannels("half", Set.of("reset"), Set.of())));
        assertTrue(!TICKER.servesTheModel(OBSERVER), "it receives an output: it watches");
        assertTrue(!TICKER.servesTheModel(new ServedChannels("idle", Set.of(), Set.of())));
    }
}
