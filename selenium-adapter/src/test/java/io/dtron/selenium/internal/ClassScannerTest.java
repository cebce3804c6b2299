package io.dtron.selenium.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import org.junit.jupiter.api.Test;
import org.openqa.selenium.chrome.ChromeDriver;
import org.openqa.selenium.chrome.ChromeOptions;

class ClassScannerTest {
    private final ClassLoader loader = ClassScannerTest.class.getClassLoader();

    @Test
    void findsTheClassesOfAPackageInAFolderButNotOfItsSubpackages() {
        List<String> names = ClassScanner.classesIn("io.dtron.selenium", loader).stream().map(Class::getName)
                .toList();
        assertTrue(names.contains("io.dtron.selenium.AbstractSeleniumAdapter"), names.toString());
        assertTrue(names.contains("io.dtron.selenium.TestSite"), "test classes too: " + names);
        assertTrue(names.contains("io.dtron.selenium.HeadlessChrome$Builder"), "nested classes too: " + names);
        assertTrue(names.stream().noneMatch(n -> n.startsWith("io.dtron.selenium.sample.")), names.toString());
        assertTrue(names.stream().noneMatch(n -> n.endsWith("package-info")), names.toString());
    }

    @Test
    void findsTheClassesOfAPackageInAJar() {
        List<Class<?>> classes = ClassScanner.classesIn("org.openqa.selenium.chrome", loader);
        assertTrue(classes.contains(ChromeDriver.class), classes.toString());
        assertTrue(classes.contains(ChromeOptions.class), classes.toString());
    }

    @Test
    void anUnknownPackageHasNoClassesAndAMalformedNameIsRefused() {
        assertEquals(List.of(), ClassScanner.classesIn("io.dtron.nothing.here", loader));
        assertEquals("no package name: 'io..dtron'",
                assertThrows(IllegalArgumentException.class, () -> ClassScanner.classesIn("io..dtron", loader))
                        .getMessage());
    }
}
