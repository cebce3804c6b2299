package io.dtron.engine.internal.zone;

import static io.dtron.engine.internal.zone.Bound.INFINITY;
import static io.dtron.engine.internal.zone.Bound.MAX_VALUE;
import static io.dtron.engine.internal.zone.Bound.le;
import static io.dtron.engine.internal.zone.Bound.lt;
import static io.dtron.engine.internal.zone.Zones.assertCanonical;
import static io.dtron.engine.internal.zone.Zones.point;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

/** Hand-checked examples for every zone operation; clocks are x1 and x2 unless said otherwise. */
class DbmTest {

    /** The zone of one clock x1 with {@code lo <= x1 <= hi}. */
    private static Dbm interval(int lo, int hi) {
        Dbm z = Dbm.unconstrained(2);
        z.constrain(0, 1, le(-lo));
        z.constrain(1, 0, le(hi));
        return z;
    }

    /** The zone of two clocks with 0 <= x1 - x2 <= 3 and x1 <= 5, reached by a small run. */
    private static Dbm staggered() {
        Dbm z = Dbm.zero(3);
        z.up();
        z.constrain(1, 0, le(3));
        z.reset(2, 0);
        z.up();
        z.constrain(1, 0, le(5));
        return z;
    }

    @Test
    void zeroZoneHoldsOnlyTheOrigin() {
        Dbm z = Dbm.zero(3);
        assertEquals(3, z.dimension());
        assertFalse(z.isEmpty());
        assertTrue(z.contains(point(0, 0), 1));
        assertFalse(z.contains(point(1, 1), 4));
        assertFalse(z.contains(point(0, 1), 4));
        assertEquals(le(0), z.upperBound(1));
        assertEquals(le(0), z.lowerBound(2));
        assertEquals("x1==0, x2==0", z.toString());
        assertCanonical(z);
    }

    @Test
    void unconstrainedZoneHoldsEveryNonNegativeValuation() {
        Dbm z = Dbm.unconstrained(3);
        assertTrue(z.contains(point(100, 3), 1));
        assertTrue(z.contains(point(0, 7), 2));
        assertFalse(z.contains(point(-1, 3), 2));
        assertEquals(INFINITY, z.upperBound(1));
        assertEquals(le(0), z.lowerBound(1));
        assertEquals(INFINITY, z.lowerBound(1, 2));
        assertEquals("true", z.toString());
        assertCanonical(z);
    }

    @Test
    void dimensionOneHasOnlyTheEmptyValuation() {
        Dbm z = Dbm.zero(1);
        assertEquals(Dbm.unconstrained(1), z);
        z.up();
        z.down();
        assertTrue(z.contains(new long[1], 1));
        assertEquals("true", z.toString());
        assertThrows(IllegalArgumentException.class, () -> Dbm.zero(0));
    }

    @Test
    void upLetsAllClocksAdvanceTogether() {
        Dbm z = Dbm.zero(3);
        z.up();
        assertTrue(z.contains(point(3, 3), 1));
        assertTrue(z.contains(point(5, 5), 2));
        assertFalse(z.contains(point(3, 2), 1));
        assertEquals(INFINITY, z.upperBound(1));
        assertEquals(le(0), z.upperBound(1, 2));
        assertEquals("x1-x2==0", z.toString());
        assertCanonical(z);
    }

    @Test
    void strictAndNonStrictUpperBounds() {
        Dbm le = Dbm.unconstrained(2);
        assertTrue(le.constrain(1, 0, le(5)));
        assertTrue(le.contains(point(5), 1));
        assertFalse(le.contains(point(501), 100));
        Dbm lt = Dbm.unconstrained(2);
        assertTrue(lt.constrain(1, 0, lt(5)));
        assertFalse(lt.contains(point(5), 1));
        assertTrue(lt.contains(point(499), 100));
        assertEquals("x1<5", lt.toString());
        assertTrue(lt.isSubsetOf(le));
        assertFalse(le.isSubsetOf(lt));
    }

    @Test
    void strictAndNonStrictLowerBounds() {
        Dbm z = Dbm.unconstrained(2);
        z.constrain(0, 1, lt(-2));
        z.constrain(1, 0, lt(5));
        assertFalse(z.contains(point(2), 1));
        assertTrue(z.contains(point(201), 100));
        assertEquals(lt(2), z.lowerBound(1));
        assertEquals("x1>2, x1<5", z.toString());
        z.constrain(0, 1, le(-3));
        assertEquals(le(3), z.lowerBound(1));
        assertEquals("x1>=3, x1<5", z.toString());
    }

    @Test
    void contradictoryBoundsGiveTheEmptyZone() {
        Dbm z = interval(3, 10);
        assertFalse(z.constrain(1, 0, lt(3)));
        assertTrue(z.isEmpty());
        assertFalse(z.contains(point(3), 1));
        assertEquals("false", z.toString());
        Dbm point = interval(3, 10);
        assertTrue(point.constrain(1, 0, le(3)));
        assertEquals("x1==3", point.toString());
        assertFalse(Dbm.unconstrained(2).constrain(0, 0, lt(0)), "x0 - x0 < 0 is false");
        assertTrue(Dbm.unconstrained(2).constrain(1, 1, le(0)), "x1 - x1 <= 0 is true");
    }

    @Test
    void contradictoryDifferencesGiveTheEmptyZone() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(1, 2, le(1));
        assertFalse(z.copy().constrain(2, 1, lt(-1)));
        assertTrue(z.constrain(2, 1, le(-1)));
        assertEquals("x1>=1, x1-x2==1", z.toString());
        assertEquals(le(1), z.lowerBound(1, 2));
        assertEquals(le(1), z.lowerBound(1), "x1 = x2 + 1 >= 1");
    }

    @Test
    void closureDerivesBoundsOfClocksAndDifferences() {
        Dbm z = staggered();
        assertEquals(le(5), z.upperBound(1));
        assertEquals(le(5), z.upperBound(2));
        assertEquals(le(3), z.upperBound(1, 2));
        assertEquals(le(0), z.lowerBound(1, 2));
        assertEquals(le(-3), z.lowerBound(2, 1));
        assertEquals(le(0), z.upperBound(2, 1));
        assertEquals("x1<=5, x2<=5, x1-x2>=0, x1-x2<=3", z.toString());
        assertTrue(z.contains(point(5, 2), 1));
        assertFalse(z.contains(point(5, 1), 1));
        assertFalse(z.contains(point(2, 3), 1));
        assertCanonical(z);
        z.constrain(2, 1, lt(0));
        assertEquals("x1>0, x1<=5, x2<5, x1-x2>0, x1-x2<=3", z.toString());
        assertFalse(z.contains(point(2, 2), 1));
    }

    @Test
    void satisfiesAsksWhetherTheZoneMeetsAConstraint() {
        Dbm z = interval(2, 5);
        assertFalse(z.satisfies(1, 0, lt(2)));
        assertTrue(z.satisfies(1, 0, le(2)));
        assertFalse(z.satisfies(0, 1, lt(-5)), "x1 > 5");
        assertTrue(z.satisfies(0, 1, le(-5)), "x1 >= 5");
        assertTrue(z.satisfies(0, 1, INFINITY));
        Dbm s = staggered();
        assertTrue(s.satisfies(1, 2, le(0)));
        assertFalse(s.satisfies(1, 2, lt(0)));
        assertFalse(s.satisfies(2, 1, lt(-3)), "x1 - x2 > 3");
    }

    @Test
    void resetAssignsAConstant() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(1, 0, le(2));
        z.reset(2, 4);
        assertEquals("x1<=2, x2==4", z.toString());
        assertEquals(le(-2), z.upperBound(1, 2));
        assertEquals(le(-4), z.lowerBound(1, 2));
        z.up();
        assertEquals("x2>=4, x1-x2>=-4, x1-x2<=-2", z.toString());
        assertTrue(z.contains(point(7, 10), 1));
        assertFalse(z.contains(point(7, 8), 1));
        z.reset(2, 0);
        assertEquals("x2==0", z.toString());
        assertCanonical(z);
    }

    @Test
    void shiftSetsAClockBackKeepingItsDistances() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(1, 0, le(2));
        z.reset(2, 4);
        z.up();
        z.constrain(2, 0, le(9));
        z.constrain(0, 2, le(-6)); // 6 <= x2 <= 9, x1 - x2 in [-4, -2]
        z.shift(2, 6);
        assertEquals("x1>=2, x1<=7, x2<=3, x1-x2>=2, x1-x2<=4", z.toString());
        assertCanonical(z);
        assertTrue(z.contains(point(5, 2), 1));
        assertFalse(z.contains(point(5, 4), 1));
        // a clock at one value set back by that value: the same zone as its reset to 0
        Dbm exact = staggered();
        exact.constrain(0, 1, le(-3));
        exact.constrain(1, 0, le(3));
        Dbm reset = exact.copy();
        reset.reset(1, 0);
        exact.shift(1, 3);
        assertEquals(reset, exact);
        assertThrows(IllegalArgumentException.class, () -> reset.shift(1, 1), "x1 is not at least 1");
    }

    @Test
    void freeForgetsOneClock() {
        Dbm z = staggered();
        z.free(1);
        assertEquals("x2<=5", z.toString());
        assertTrue(z.contains(point(100, 1), 1));
        assertCanonical(z);
    }

    @Test
    void copyClockAssignsOneClockToAnother() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(0, 2, le(-1));
        z.constrain(2, 0, le(2));
        z.copyClock(1, 2);
        assertEquals("x1>=1, x1<=2, x2>=1, x2<=2, x1-x2==0", z.toString());
        assertCanonical(z);
        Dbm viaReset = z.copy();
        viaReset.reset(1, 0);
        z.copyClock(1, 0);
        assertEquals(viaReset, z);
        Dbm same = z.copy();
        z.copyClock(2, 2);
        assertEquals(same, z);
    }

    @Test
    void downGoesBackInTime() {
        Dbm z = Dbm.unconstrained(3);
        z.reset(1, 3);
        z.reset(2, 1);
        z.down();
        assertEquals("x1>=2, x1<=3, x2<=1, x1-x2==2", z.toString());
        assertTrue(z.contains(point(5, 1), 2));
        assertFalse(z.contains(point(3, 0), 2));
        assertCanonical(z);
        Dbm zero = Dbm.zero(3);
        zero.down();
        assertEquals(Dbm.zero(3), zero);
    }

    @Test
    void intersectionAndEmptyIntersection() {
        Dbm a = interval(0, 3);
        Dbm b = interval(2, 10);
        assertTrue(a.intersect(b));
        assertEquals(interval(2, 3), a);
        Dbm c = Dbm.unconstrained(2);
        c.constrain(0, 1, lt(-3));
        assertFalse(a.intersect(c));
        assertTrue(a.isEmpty());
        Dbm d = interval(0, 3);
        assertTrue(d.intersect(Dbm.unconstrained(2)));
        assertEquals(interval(0, 3), d);
    }

    @Test
    void relationOfZones() {
        Dbm small = interval(0, 3);
        Dbm big = interval(0, 5);
        Dbm other = interval(2, 7);
        Dbm empty = interval(4, 3);
        assertTrue(empty.isEmpty());
        assertEquals(Relation.SUBSET, small.relation(big));
        assertEquals(Relation.SUPERSET, big.relation(small));
        assertEquals(Relation.EQUAL, small.relation(small.copy()));
        assertEquals(Relation.DIFFERENT, small.relation(other));
        assertEquals(Relation.EQUAL, empty.relation(interval(9, 1)));
        assertEquals(Relation.SUBSET, empty.relation(small));
        assertEquals(Relation.SUPERSET, small.relation(empty));
        assertTrue(empty.isSubsetOf(small));
        assertFalse(small.isSubsetOf(empty));
        assertTrue(small.isSubsetOf(big));
        assertFalse(big.isSubsetOf(small));
    }

    @Test
    void equalityIsEqualityOfSets() {
        Dbm a = Dbm.zero(3);
        Dbm b = Dbm.unconstrained(3);
        b.constrain(1, 0, le(0));
        b.constrain(2, 0, le(0));
        assertEquals(a, b);
        assertEquals(a.hashCode(), b.hashCode());
        assertNotEquals(Dbm.zero(2), Dbm.zero(3));
        assertNotEquals(Dbm.zero(2), Dbm.unconstrained(2));
        assertNotEquals(Dbm.zero(2), "x1==0");
        assertEquals(interval(4, 3), interval(9, 1), "empty zones are equal");
    }

    @Test
    void copiesAreIndependent() {
        Dbm z = staggered();
        Dbm copy = z.copy();
        copy.up();
        assertNotEquals(z, copy);
        Dbm target = Dbm.zero(3);
        target.copyFrom(z);
        assertEquals(z, target);
        target.free(2);
        assertEquals(staggered(), z);
        assertThrows(IllegalArgumentException.class, () -> target.copyFrom(Dbm.zero(2)));
    }

    @Test
    void toStringWithClockNames() {
        Dbm z = staggered();
        assertEquals("x<=5, y<=5, x-y>=0, x-y<=3", z.toString(new String[] {"t0", "x", "y"}));
        assertThrows(IllegalArgumentException.class, () -> z.toString(new String[] {"x"}));
    }

    @Test
    void extrapolateMaxBoundsWeakensBoundsAboveTheMaximum() {
        int[] max = {0, 2, 2};
        Dbm z = Dbm.unconstrained(3);
        z.reset(1, 3);
        z.extrapolateMaxBounds(max);
        assertEquals("x1>2", z.toString());
        Dbm below = Dbm.unconstrained(3);
        below.constrain(1, 0, le(2));
        below.constrain(0, 2, le(-2));
        Dbm unchanged = below.copy();
        below.extrapolateMaxBounds(max);
        assertEquals(unchanged, below, "x1 <= 2 and x2 >= 2 reach the maximum but do not pass it");
        Dbm diagonal = Dbm.unconstrained(3);
        diagonal.reset(1, 5);
        diagonal.reset(2, 0);
        diagonal.up();
        diagonal.extrapolateMaxBounds(max);
        assertEquals("x1>2, x1-x2>2", diagonal.toString());
    }

    @Test
    void extrapolateMaxBoundsFreesClocksWithoutConstants() {
        Dbm z = Dbm.unconstrained(3);
        z.reset(1, 3);
        z.reset(2, 1);
        Dbm freed = z.copy();
        freed.free(1);
        z.extrapolateMaxBounds(new int[] {0, -1, 5});
        assertEquals(freed, z);
        assertEquals("x2==1", z.toString());
    }

    @Test
    void extrapolateLuUsesLowerAndUpperBoundsSeparately() {
        Dbm upper = interval(1, 5);
        upper.extrapolateLU(new int[] {0, 2}, new int[] {0, 10});
        assertEquals("x1>=1", upper.toString(), "an upper bound above L is dropped");
        Dbm lower = Dbm.unconstrained(2);
        lower.constrain(0, 1, le(-7));
        lower.extrapolateLU(new int[] {0, 10}, new int[] {0, 3});
        assertEquals("x1>3", lower.toString(), "a lower bound above U is weakened");
        Dbm kept = interval(1, 5);
        kept.extrapolateMaxBounds(new int[] {0, 10});
        assertEquals(interval(1, 5), kept);
        Dbm all = staggered();
        all.extrapolateLU(new int[] {0, -1, -1}, new int[] {0, -1, -1});
        assertEquals(Dbm.unconstrained(3), all);
    }

    @Test
    void extrapolateLuPlusDropsDifferencesOfClocksAboveTheirBounds() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(2, 0, le(1));
        z.reset(1, 5);
        Dbm m = z.copy();
        z.extrapolateLU(new int[] {0, 3, 3}, new int[] {0, 3, 3});
        assertEquals("x1>3, x2<=1", z.toString());
        m.extrapolateMaxBounds(new int[] {0, 3, 3});
        assertEquals("x1>3, x2<=1, x1-x2>3", m.toString());
    }

    @Test
    void boundsNearTheRangeStayExact() {
        int big = 1 << 29;
        Dbm z = Dbm.zero(3);
        z.reset(1, big);
        z.up();
        z.constrain(1, 0, le(big + 5));
        assertEquals(le(5), z.upperBound(2));
        assertEquals(le(big), z.upperBound(1, 2));
        assertTrue(z.contains(point(big + 5L, 5), 1));
        assertFalse(z.contains(point(big + 5L, 6), 1));
        Dbm far = Dbm.unconstrained(2);
        far.reset(1, MAX_VALUE);
        assertEquals(le(MAX_VALUE), far.lowerBound(1));
        assertFalse(far.constrain(1, 0, lt(MAX_VALUE)));
    }

    @Test
    void derivedBoundsBeyondTheRangeAreDroppedNotWrapped() {
        Dbm z = Dbm.unconstrained(4);
        z.constrain(1, 2, le(MAX_VALUE));
        z.constrain(2, 3, le(MAX_VALUE));
        assertFalse(z.isEmpty());
        assertEquals(INFINITY, z.upperBound(1, 3), "x1 - x3 <= 2 * MAX_VALUE is not representable");
        assertTrue(z.contains(point(2L * MAX_VALUE, MAX_VALUE, 0), 1));
        assertFalse(z.contains(point(2L * MAX_VALUE + 1, MAX_VALUE, 0), 1));
    }

    @Test
    void containsChecksItsArguments() {
        Dbm z = Dbm.unconstrained(3);
        z.constrain(1, 0, le(MAX_VALUE));
        assertThrows(IllegalArgumentException.class, () -> z.contains(new long[2], 1));
        assertThrows(IllegalArgumentException.class, () -> z.contains(new long[3], 0));
        assertThrows(ArithmeticException.class, () -> z.contains(new long[3], Long.MAX_VALUE / 2));
    }

    @Test
    void operationsCheckTheirArguments() {
        Dbm z = Dbm.unconstrained(3);
        assertThrows(IndexOutOfBoundsException.class, () -> z.constrain(3, 0, le(1)));
        assertThrows(IndexOutOfBoundsException.class, () -> z.upperBound(-1, 0));
        assertThrows(IndexOutOfBoundsException.class, () -> z.reset(0, 1));
        assertThrows(IndexOutOfBoundsException.class, () -> z.free(3));
        assertThrows(IndexOutOfBoundsException.class, () -> z.copyClock(1, 3));
        assertThrows(IllegalArgumentException.class, () -> z.reset(1, -1));
        assertThrows(IllegalArgumentException.class, () -> z.reset(1, MAX_VALUE + 1));
        assertThrows(IllegalArgumentException.class, () -> z.extrapolateMaxBounds(new int[2]));
        assertThrows(IllegalArgumentException.class, () -> z.extrapolateLU(new int[3], new int[4]));
        assertThrows(IllegalArgumentException.class, () -> z.intersect(Dbm.zero(2)));
        assertThrows(IllegalArgumentException.class, () -> z.relation(Dbm.zero(2)));
        assertThrows(IllegalArgumentException.class, () -> z.isSubsetOf(Dbm.zero(4)));
        assertEquals(Dbm.unconstrained(3), z, "failed calls leave the zone unchanged");
    }
}
