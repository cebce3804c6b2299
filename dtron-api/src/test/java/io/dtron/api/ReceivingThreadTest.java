package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.internal.TesterSide;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Listeners that may be called on the transport's receiving thread ({@link DtronListener#onReceivingThread}), over
 * TCP on loopback: still one message at a time and in the bus's order, beside listeners of the listeners' thread that
 * block; one of them may not send.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class ReceivingThreadTest {
    private static final Duration WAIT = Duration.ofSeconds(30);
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final IDtronChannel hold = IDtronChannel.of("hold", "amount");
    private final String cluster = TestClusters.uniqueName("receiving");
    private final int port = FreePorts.range(FreePorts.BUS_RANGE);

    private DtronOptions.Builder options(String name) {
        return DtronOptions.builder().clusterName(cluster).memberName(name).port(port)
                .portRange(FreePorts.BUS_RANGE);
    }

    /** What one member's listeners saw, of both channels, in the order they were called. */
    private static final class Seen {
        final List<String> messages = new CopyOnWriteArrayList<>();
        final AtomicInteger inListeners = new AtomicInteger();
        final AtomicInteger mostAtOnce = new AtomicInteger();
        final AtomicInteger onReceivingThread = new AtomicInteger();

        void add(IDtronChannelValued message) {
            mostAtOnce.accumulateAndGet(inListeners.incrementAndGet(), Math::max);
            if (!Thread.currentThread().getName().startsWith("dtron-listeners-")) {
                onReceivingThread.incrementAndGet();
            }
            messages.add(message.getChannelName() + ":" + message.getSender() + ":"
                    + message.getVariables().get("amount"));
            inListeners.decrementAndGet();
        }
    }

    @Test
    void messagesOfSeveralSendersReachTheListenersOneAtATimeInTheSameOrderEverywhereBesideABlockingListener()
            throws Exception {
        int perSender = 60;
        CountDownLatch release = new CountDownLatch(1);
        try (Dtron a = Dtron.connect(options("a").build());
                Dtron b = Dtron.connect(options("b").build());
                Dtron c = Dtron.connect(options("c").build())) {
            assertTrue(a.awaitMembers(3, WAIT));
            List<Dtron> members = List.of(a, b, c);
            List<Seen> seen = new ArrayList<>();
            for (Dtron member : members) {
                Seen own = new Seen();
                seen.add(own);
                member.addDtronListener(new DtronListener(move) {
                    @Override
                    public void messageReceived(IDtronChannelValued message) {
                        own.add(message);
                    }

                    @Override
                    protected boolean onReceivingThread() {
                        return true;
                    }
                });
                member.addDtronListener(new DtronListener(hold) {
                    @Override
                    public void messageReceived(IDtronChannelValued message) {
                        own.add(message);
                        if (member == a) {
                            // member a's listeners' thread blocks: the moves received meanwhile must wait behind it
                            try {
                                release.await();
                            } catch (InterruptedException e) {
                                Thread.currentThread().interrupt();
                            }
                        }
                    }
                });
            }
            for (Dtron member : members) {
                Waits.await("every member serves both channels").until(() -> members.stream()
                        .allMatch(m -> m == member || receives(member, m, "move") && receives(member, m, "hold")));
            }
            b.send(hold.constructValued(Map.of("amount", 0)));
            List<CompletableFuture<Void>> sending = new ArrayList<>();
            for (Dtron sender : List.of(b, c)) {
                sending.add(CompletableFuture.runAsync(() -> {
                    for (int i = 1; i <= perSender; i++) {
                        sender.send(move.constructValued(Map.of("amount", i)));
                    }
                }));
            }
            for (CompletableFuture<Void> future : sending) {
                future.get(WAIT.toSeconds(), TimeUnit.SECONDS);
            }
            int all = 1 + 2 * perSender;
            Waits.await("b and c received every message").until(() -> seen.get(1).messages.size() == all
                    && seen.get(2).messages.size() == all);
            assertEquals(1, seen.get(0).messages.size(), "a's listeners still hold the first message");
            release.countDown();
            Waits.await("a received every message").until(() -> seen.get(0).messages.size() == all);

            assertEquals(seen.get(0).messages, seen.get(1).messages, "a and b saw the same order");
            assertEquals(seen.get(0).messages, seen.get(2).messages, "a and c saw the same order");
            for (Seen own : seen) {
                assertEquals(1, own.mostAtOnce.get(), "one message at a time");
                for (Dtron sender : List.of(b, c)) {
                    List<String> fromSender = own.messages.stream()
                            .filter(m -> m.startsWith("move:" + sender.getMemberId() + ":")).toList();
                    List<String> expected = new ArrayList<>();
                    for (int i = 1; i <= perSender; i++) {
                        expected.add("move:" + sender.getMemberId() + ":" + i);
                    }
                    assertEquals(expected, fromSender, "each sender's moves in the order sent");
                }
            }
        }
    }

    @Test
    void aListenerOnTheReceivingThreadMayNotSendAndItsInputIsAcknowledgedAfterIt() throws Exception {
        try (Dtron tester = Dtron.connect(options("tester").build());
                Dtron adapter = Dtron.connect(options("adapter").build())) {
            assertTrue(tester.awaitMembers(2, WAIT));
            CompletableFuture<String> thread = new CompletableFuture<>();
            CompletableFuture<RuntimeException> refused = new CompletableFuture<>();
            adapter.addDtronListener(new DtronListener(move) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    thread.complete(Thread.currentThread().getName());
                    try {
                        getDtron().send(hold.constructValued(Map.of("amount", 1)));
                        refused.complete(null);
                    } catch (RuntimeException e) {
                        refused.complete(e);
                    }
                }

                @Override
                protected boolean onReceivingThread() {
                    return true;
                }
            });
            Inbox acks = new Inbox(Dtron.ACK);
            tester.addDtronListener(acks);
            // the adapter's listeners' thread hears of the tester's last change of what it serves (tester, sends move)
            java.util.concurrent.atomic.AtomicBoolean heard = new java.util.concurrent.atomic.AtomicBoolean();
            TesterSide.of(adapter).addServedChannelsListener(others -> {
                ServedChannels s = others.get(tester.getMemberId());
                if (s != null && s.tester() && s.sends().contains("move")) {
                    heard.set(true);
                }
            });
            tester.declareOutputs(move);
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1000)));
            Waits.await("each knows what the other serves").until(() -> receives(tester, adapter, "move")
                    && heard.get());
            // the adapter's listeners are idle and nothing more is queued for them (no member's served channels
            // change now): the input is delivered on the thread that received it
            assertTrue(TesterSide.of(adapter).awaitListeners(WAIT));
            IDtronChannelValued input = tester.send(move.constructValued(Map.of("amount", 7)));

            assertFalse(thread.get(WAIT.toSeconds(), TimeUnit.SECONDS).startsWith("dtron-listeners-"),
                    "called on the receiving thread");
            RuntimeException e = refused.get(WAIT.toSeconds(), TimeUnit.SECONDS);
            assertTrue(e instanceof IllegalStateException && e.getMessage().contains("receiving thread"),
                    "send refused with a reason: " + e);
            IDtronChannelValued ack = acks.take();
            assertEquals(List.of(tester.getMemberId(), input.getSequence(), adapter.getMemberId()),
                    List.of(ack.getAckedSender(), ack.getAckedSequence(), ack.getSender()));
        }
    }

    /** What {@code who} knows {@code member} serves. */
    private static java.util.Optional<ServedChannels> served(Dtron who, Dtron member) {
        return java.util.Optional.ofNullable(TesterSide.of(who).getMembersServedChannels().get(member.getMemberId()));
    }

    private static boolean receives(Dtron who, Dtron member, String channel) {
        return served(who, member).map(s -> s.receives().contains(channel)).orElse(false);
    }
}
