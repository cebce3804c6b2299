package io.dtron.selenium.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.selenium.AdapterException;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.openqa.selenium.By;

class LocatorsTest {
    private final Locators locators = new Locators(Map.of("LOGIN_BUTTON", "id:login-button",
            "ROWS", "css:#list tr", "BROKEN", "login-button"));

    @Test
    void everyStrategyIsALocator() {
        assertEquals(By.id("a"), locators.resolve("id:a").by());
        assertEquals(By.name("a"), locators.resolve("name:a").by());
        assertEquals(By.cssSelector("#a b"), locators.resolve("css:#a b").by());
        assertEquals(By.xpath("//h1[@x='1']"), locators.resolve("xpath://h1[@x='1']").by());
        assertEquals(By.linkText("Log out"), locators.resolve("link:Log out").by());
        assertEquals(By.partialLinkText("Log"), locators.resolve("partialLink:Log").by());
        assertEquals(By.className("status"), locators.resolve("class:status").by());
        assertEquals(By.tagName("table"), locators.resolve("tag:table").by());
    }

    @Test
    void keysAreLookedUpAndNamedWithTheirLocator() {
        Locators.Locator login = locators.resolve("LOGIN_BUTTON");
        assertEquals(By.id("login-button"), login.by());
        assertEquals("LOGIN_BUTTON (id:login-button)", login.toString());
        assertEquals(By.cssSelector("#list tr"), locators.resolve("ROWS").by());
        assertEquals("id:x", locators.resolve("id:x").toString());
    }

    @Test
    void unknownKeysAndValuesThatAreNoLocatorsSayWhy() {
        assertEquals("'LOGOUT' is neither a key of the adapters' properties nor a locator (class:, css:, id:, link:,"
                + " name:, partialLink:, tag:, xpath:)",
                assertThrows(AdapterException.class, () -> locators.resolve("LOGOUT")).getMessage());
        assertEquals("the value of BROKEN, 'login-button', is no locator: start it with one of class:, css:, id:,"
                + " link:, name:, partialLink:, tag:, xpath:",
                assertThrows(AdapterException.class, () -> locators.resolve("BROKEN")).getMessage());
        assertThrows(AdapterException.class, () -> locators.resolve("id:"));
    }

    @Test
    void xpathLiteralsQuoteAnyText() {
        assertEquals("'On'", Locators.xpathLiteral("On"));
        assertEquals("\"Tom's\"", Locators.xpathLiteral("Tom's"));
        assertEquals("concat('say \"hi\" to ', \"'\", 'em')", Locators.xpathLiteral("say \"hi\" to 'em"));
    }
}
