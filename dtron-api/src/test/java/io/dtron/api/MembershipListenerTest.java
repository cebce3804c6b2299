package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** Membership listeners hear of joins and leaves, in order with the messages. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class MembershipListenerTest {
    private static final Duration WAIT = Duration.ofSeconds(10);
    private final String cluster = TestClusters.uniqueName("membership");
    private final IDtronChannel note = IDtronChannel.of("note", "n");

    @Test
    void joinsAndLeavesComeAfterTheMessagesBeforeThem() throws Exception {
        BlockingQueue<String> events = new LinkedBlockingQueue<>();
        try (Dtron watcher = Dtron.connect(TestClusters.inJvm(cluster).memberName("watcher").build())) {
            watcher.addDtronListener(new DtronListener(note) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    events.add("note " + message.getVariables().get("n"));
                }
            });
            DtronMembershipListener listener = (members, joined, left) ->
                    events.add("members " + members + " joined " + joined + " left " + left);
            watcher.addMembershipListener(listener);
            watcher.addMembershipListener(listener);
            try (Dtron other = Dtron.connect(TestClusters.inJvm(cluster).memberName("other").build())) {
                assertEquals("members [watcher, other] joined [other] left []", take(events));
                for (int n = 1; n <= 3; n++) {
                    other.send(note.constructValued(Map.of("n", n)));
                }
            }
            assertEquals(List.of("note 1", "note 2", "note 3", "members [watcher] joined [] left [other]"),
                    List.of(take(events), take(events), take(events), take(events)));
            assertNull(events.poll(100, TimeUnit.MILLISECONDS), "a listener added twice is called once");

            watcher.removeMembershipListener(listener);
            try (Dtron again = Dtron.connect(TestClusters.inJvm(cluster).memberName("again").build())) {
                assertTrue(watcher.awaitMembers(2, WAIT));
                assertNull(events.poll(200, TimeUnit.MILLISECONDS), "a removed listener hears nothing");
            }
        }
    }

    @Test
    void aFailingListenerIsCountedAndOthersStillHear() throws Exception {
        BlockingQueue<List<String>> joins = new LinkedBlockingQueue<>();
        try (Dtron watcher = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            watcher.addMembershipListener((members, joined, left) -> {
                throw new IllegalStateException("listener bug");
            });
            watcher.addMembershipListener((members, joined, left) -> joins.add(joined));
            try (Dtron other = Dtron.connect(TestClusters.inJvm(cluster).memberName("other").build())) {
                assertEquals(List.of("other"), joins.poll(10, TimeUnit.SECONDS));
                assertEquals(1, watcher.getStats().getListenerFailures());
            }
        }
    }

    private static String take(BlockingQueue<String> events) throws InterruptedException {
        String event = events.poll(10, TimeUnit.SECONDS);
        assertNotNull(event, "nothing within 10 s");
        return event;
    }
}
