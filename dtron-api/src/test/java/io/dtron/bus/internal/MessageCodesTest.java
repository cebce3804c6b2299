package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.bus.internal.DropReason;
import java.nio.charset.StandardCharsets;
import java.util.HexFormat;
import org.junit.jupiter.api.Test;

/**
 * The message codes against the test vectors of security.md (which the Python and C members check too), and the
 * check of received messages: unauthenticated, replayed, stale, in this order.
 */
class MessageCodesTest {
    /** The secret of the vectors: a key file's 64 hexadecimal digits. */
    static final byte[] SECRET = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"
            .getBytes(StandardCharsets.UTF_8);
    private static final MessageCodes CODES = MessageCodes.forSecret(SECRET);
    private static final byte[] TICK = HexFormat.of().parseHex("0a047469636b");
    private static final long T = 1_764_201_600_000_000_000L;

    /** The vectors as security.md gives them (computed with Java's Mac, and again with openssl). */
    @Test
    void theVectorsOfSecurityMd() {
        assertEquals("f28112d382ab034e8ca1f42619cae5d0c5e52dc410ee18ab708c3612f228a321",
                HexFormat.of().formatHex(MessageCodes.key(SECRET)), "K");
        assertEquals("5f724ebae3c605c2e2c63bd6f1cbc45de0d29bae2ef962c34a367bd024442564",
                CODES.code("dtron.lab.c.tick", "ticker", "1764201600000000000", "1764201600000000123", null, null,
                        TICK), "a channel message");
        assertEquals("406580bc815ae38aa0f6313097632b5ad936352ee2e15e2db6aacf10a529d109",
                CODES.code("dtron.lab.p", "dtron-4242-0a1b2c3d", "1764201600000000007", "1764201601000000000",
                        "alive", "3", new byte[0]), "an alive");
        assertEquals("f1ff465197706229fb063521b2ac769d2e034557e04734bba05391ed34ad7c6e",
                CODES.code("dtron.lab.p", "tester", "1764201600000000001", "1764201600000000002", "join", null,
                        null), "a join");
    }

    @Test
    void anAbsentHeaderCountsAsEmptyAndEveryItemIsFramedByItsLength() {
        String absent = CODES.code("s", "a", "1", "2", null, null, null);
        assertEquals(absent, CODES.code("s", "a", "1", "2", "", "", new byte[0]));
        // the same bytes split differently between items make another code
        assertFalse(CODES.code("s", "ab", "1", "2", null, null, null)
                .equals(CODES.code("s", "a", "b1", "2", null, null, null)));
        assertEquals(64, absent.length());
        assertTrue(absent.matches("[0-9a-f]{64}"));
    }

    @Test
    void anEmptySecretOrKeyIsRefused() {
        assertThrows(IllegalArgumentException.class, () -> MessageCodes.forSecret(new byte[0]));
        assertThrows(IllegalArgumentException.class, () -> MessageCodes.forKey(new byte[0]));
    }

    /** Checks a message of {@code sender} whose code the codes made, stored at {@code stored}. */
    private static DropReason signed(MessageCodes.Check check, MessageCodes codes, String sender, String seq,
            String time, long stored) {
        String mac = codes.code("dtron.lab.c.tick", sender, seq, time, null, null, TICK);
        return check.check("dtron.lab.c.tick", sender, seq, time, null, null, TICK, mac, stored);
    }

    private static DropReason signed(MessageCodes.Check check, String sender, long seq) {
        return signed(check, CODES, sender, Long.toString(seq), Long.toString(T), T);
    }

    @Test
    void aMessageWithoutItsCodeIsUnauthenticated() {
        MessageCodes.Check check = CODES.check();
        String seq = "1";
        String time = Long.toString(T);
        String mac = CODES.code("dtron.lab.c.tick", "ticker", seq, time, null, null, TICK);
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tick", "ticker", seq, time, null, null, TICK, null, T), "no code");
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tock", "ticker", seq, time, null, null, TICK, mac, T), "another subject");
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tick", "tester", seq, time, null, null, TICK, mac, T), "another sender");
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tick", "ticker", seq, time, "leave", null, TICK, mac, T), "a presence");
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tick", "ticker", seq, time, null, null, new byte[] {1}, mac, T), "data");
        assertEquals(DropReason.UNAUTHENTICATED,
                check.check("dtron.lab.c.tick", "ticker", seq, time, null, null, TICK, mac.toUpperCase(), T),
                "the code's digits are lowercase");
        assertEquals(DropReason.UNAUTHENTICATED, signed(check, MessageCodes.forSecret("guess".getBytes(
                StandardCharsets.UTF_8)), "ticker", seq, time, T), "another secret");
        assertNull(check.check("dtron.lab.c.tick", "ticker", seq, time, null, null, TICK, mac, T), "the real one");
    }

    @Test
    void aCounterAcceptedBeforeOrMissingOrNoNumberIsReplayed() {
        MessageCodes.Check check = CODES.check();
        assertNull(signed(check, "ticker", 5000));
        assertEquals(DropReason.REPLAYED, signed(check, "ticker", 5000), "the same again");
        assertNull(signed(check, "tester", 5000), "another sender's counters are its own");
        assertNull(signed(check, "ticker", 4999), "a lower one not seen yet, within the window");
        assertEquals(DropReason.REPLAYED, signed(check, "ticker", 4999));
        assertNull(signed(check, "ticker", 905), "4095 below the highest: still in the window");
        assertEquals(DropReason.REPLAYED, signed(check, "ticker", 904), "4096 below the highest: too old");
        assertNull(signed(check, "ticker", 9000), "a jump ahead");
        assertEquals(DropReason.REPLAYED, signed(check, "ticker", 4999), "still within the window, and seen");
        assertNull(signed(check, "ticker", 8999));
        for (String seq : new String[] {"", "0", "-1", "+7", "12a", " 7", "99999999999999999999"}) {
            assertEquals(DropReason.REPLAYED, signed(check, CODES, "other", seq, Long.toString(T), T), seq);
        }
        String time = Long.toString(T);
        String mac = CODES.code("dtron.lab.c.tick", "other", null, time, null, null, TICK);
        assertEquals(DropReason.REPLAYED,
                check.check("dtron.lab.c.tick", "other", null, time, null, null, TICK, mac, T), "no counter");
    }

    @Test
    void aTimeMoreThan120SecondsFromTheStreamsIsStaleAndItsCounterStaysUnused() {
        MessageCodes.Check check = CODES.check();
        long limit = 120_000_000_000L;
        assertNull(signed(check, CODES, "a", "1", Long.toString(T - limit), T), "120 s behind");
        assertNull(signed(check, CODES, "a", "2", Long.toString(T + limit), T), "120 s ahead");
        assertEquals(DropReason.STALE, signed(check, CODES, "a", "3", Long.toString(T - limit - 1), T));
        assertEquals(DropReason.STALE, signed(check, CODES, "a", "3", Long.toString(T + limit + 1), T));
        assertEquals(DropReason.STALE, signed(check, CODES, "a", "3", Long.toString(T - 600_000_000_000L), T),
                "10 minutes behind");
        assertEquals(DropReason.STALE, signed(check, CODES, "a", "3", "", T), "no time");
        assertEquals(DropReason.STALE, signed(check, CODES, "a", "3", "-5", T), "no number");
        assertNull(signed(check, CODES, "a", "3", Long.toString(T), T), "a stale message's counter stays unused");
        assertEquals(DropReason.REPLAYED, signed(check, CODES, "a", "3", Long.toString(T - limit - 1), T),
                "replayed is checked before stale");
    }

    /**
     * A member that joins learns the counters of the stream's messages before its join: only those with a valid
     * code, whatever their time, and one too low for the window marks no other counter.
     */
    @Test
    void theCountersOfMessagesBeforeAJoinAreLearnedWhenTheirCodeIsValid() {
        MessageCodes.Check check = CODES.check();
        String old = Long.toString(T - 600_000_000_000L);
        String mac = CODES.code("dtron.lab.c.tick", "a", "5000", old, null, null, TICK);
        assertTrue(check.learn("dtron.lab.c.tick", "a", "5000", old, null, null, TICK, mac), "a stale one too");
        assertFalse(check.learn("dtron.lab.c.tick", "b", "7", Long.toString(T), null, null, TICK, "0".repeat(64)),
                "no valid code");
        String low = CODES.code("dtron.lab.c.tick", "a", "903", old, null, null, TICK);
        assertTrue(check.learn("dtron.lab.c.tick", "a", "903", old, null, null, TICK, low));
        assertFalse(check.learn("dtron.lab.c.tick", "a", "x", old, null, null, TICK,
                CODES.code("dtron.lab.c.tick", "a", "x", old, null, null, TICK)), "no counter");
        assertEquals(DropReason.REPLAYED, signed(check, "a", 5000), "learned");
        assertNull(signed(check, "a", 4999), "903, below the window, marked nothing (4999 shares its slot)");
        assertNull(signed(check, "a", 5001));
        assertNull(signed(check, "b", 7), "the code of b's 7 was not valid: nothing learned");
    }

    @Test
    void theWindowRemembersExactly4096CountersBelowTheHighest() {
        MessageCodes.Window window = new MessageCodes.Window();
        for (long c = 10_000; c > 10_000 - 4096; c -= 2) {
            window.add(c);
        }
        for (long c = 10_000; c > 10_000 - 4096; c--) {
            assertEquals((10_000 - c) % 2 == 0, window.holds(c), Long.toString(c));
        }
        assertTrue(window.holds(10_000 - 4096));
        window.add(10_001);
        assertTrue(window.holds(10_001 - 4096), "gone below the window");
        assertFalse(window.holds(10_001 - 4095 + 1), "odd, never added");
        window.add(10_000 + 5000);
        for (long c = 15_000 - 4095; c < 15_000; c++) {
            assertFalse(window.holds(c), "a jump forgets what the window no longer covers: " + c);
        }
    }
}
