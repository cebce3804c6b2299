package io.dtron.engine.internal.zone;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class DbmPackTest {
    @Test
    void aPackedZoneUnpacksToTheSameZoneAndKeepsInclusion() {
        Dbm small = Dbm.zero(3);
        small.up();
        small.constrain(1, 0, Bound.le(5));
        Dbm large = Dbm.unconstrained(3);
        large.constrain(1, 0, Bound.lt(10));
        short[] packedSmall = small.pack();
        short[] packedLarge = large.pack();
        assertEquals(small, Dbm.unpack(3, packedSmall));
        assertEquals(large, Dbm.unpack(3, packedLarge));
        assertTrue(small.isSubsetOf(packedLarge));
        assertFalse(large.isSubsetOf(packedSmall));
        assertTrue(large.includes(packedSmall));
        assertFalse(small.includes(packedLarge));
        assertTrue(small.includes(packedSmall) && small.isSubsetOf(packedSmall));
    }

    @Test
    void boundsBeyondAShortAreNotPacked() {
        Dbm z = Dbm.zero(2);
        z.up();
        z.constrain(1, 0, Bound.le(20_000));
        assertNull(z.pack(), "20,000 is 40,001 as a raw bound");
        z = Dbm.zero(2);
        z.up();
        z.constrain(1, 0, Bound.le(16_000));
        assertEquals(z, Dbm.unpack(2, z.pack()));
    }
}
